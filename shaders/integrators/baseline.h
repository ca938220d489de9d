// Push constants of integrators.baseline (shaders/integrators/baseline.comp), shared with
// lighting/integrators/baseline_integrator.cpp.
#ifndef LANTERN_INTEGRATORS_BASELINE_H
#define LANTERN_INTEGRATORS_BASELINE_H

#include "shared/lang.h"

LANTERN_BEGIN_SHARED

// Frame size, index, seed, light count and scene radius come from FrameConstants.
struct BaselinePush {
  uint tile_stride;  // workgroup g shades tile (g * tile_stride) mod tile count; coprime to it
};
LANTERN_STATIC_SIZE(BaselinePush, 4);

// RNG stream of the baseline pass (rng_init's `pass`).
LANTERN_CONST uint kBaselineRngPass = 0x62u;

LANTERN_END_SHARED

#endif
