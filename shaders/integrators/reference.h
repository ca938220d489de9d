// Push constants and constants of integrators.reference (shaders/integrators/reference.comp),
// shared with lighting/integrators/reference_integrator.cpp.
#ifndef LANTERN_INTEGRATORS_REFERENCE_H
#define LANTERN_INTEGRATORS_REFERENCE_H

#include "shared/lang.h"

LANTERN_BEGIN_SHARED

// Frame size, index, seed, light count and scene radius come from FrameConstants.
struct ReferencePush {
  uint tile_stride;  // workgroup g shades tile (g * tile_stride) mod tile count; coprime to it
  uint spp;          // samples per pixel this dispatch (each: one light + one BSDF sample)
};
LANTERN_STATIC_SIZE(ReferencePush, 8);

// RNG stream of the reference pass (rng_init's `pass`).
LANTERN_CONST uint kReferenceRngPass = 0x72u;

// Analytic lights up to this many are estimated by a walk through all of them at every pixel
// (reference.comp analytic_lights: two evaluations each per pixel and frame); more are drawn
// from the power alias table like emissive triangles.
LANTERN_CONST uint kReferenceAnalyticWalkMax = 4096u;
// ... and only while the walk's fixed cost is at most this many lights per sample of the frame's
// spp: at one sample per pixel the walk through night_market's 1200 lights took 12x the frame
// (and lost at equal time), at 64 samples 1.7x, at 256 1.35x (README, "The reference's analytic
// lights").
LANTERN_CONST uint kReferenceAnalyticWalkPerSample = 64u;

// Default samples per pixel per frame (IntegratorConfig.spp = 0).
LANTERN_CONST uint kReferenceDefaultSpp = 64u;

LANTERN_END_SHARED

#endif
