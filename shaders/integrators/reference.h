// Push constants and constants of integrators.reference (shaders/integrators/reference.comp),
// shared with lighting/integrators/reference_integrator.cpp.
#ifndef LANTERN_INTEGRATORS_REFERENCE_H
#define LANTERN_INTEGRATORS_REFERENCE_H

#include "shared/lang.h"

LANTERN_BEGIN_SHARED

struct ReferencePush {
  uint frame_index;    // seeds this frame's random numbers (with FrameConstants.frame.w)
  uint light_count;    // lights in the alias table; 0 = none can be sampled
  float scene_radius;  // world bounding-sphere radius: directional shadow ray length
  uint tile_stride;    // workgroup g shades tile (g * tile_stride) mod tile count; coprime to it
  uint spp;            // samples per pixel this dispatch (each: one light + one BSDF sample)
  uint pad0;
  uint pad1;
  uint pad2;
};
LANTERN_STATIC_SIZE(ReferencePush, 32);

// Pixels per side of the square tile one workgroup shades.
LANTERN_CONST uint kReferenceTileSize = 8u;

// RNG stream of the reference pass (rng_init's `pass`).
LANTERN_CONST uint kReferenceRngPass = 0x72u;

// Default samples per pixel per frame (IntegratorConfig.spp = 0).
LANTERN_CONST uint kReferenceDefaultSpp = 64u;

LANTERN_END_SHARED

#endif
