// Combining reservoirs from several domains (restir.temporal: pixel + its history; restir.spatial:
// pixel + k neighbours) with the resampling MIS weights of the bias-correction mode
// (shared/reservoir_combine.h, the loop the CPU chain tests run). Domain 0 is the canonical pixel;
// the caller defines the domain accessors (below) and calls restir_combine.
#ifndef LANTERN_RESTIR_REUSE_GLSL
#define LANTERN_RESTIR_REUSE_GLSL

#include "restir/restir_common.glsl"

// The shared combine loop (shared/reservoir_combine.h) reads the domains through
// combine_domain_reservoir(j) and combine_domain_target(j, y), and pairwise MIS through
// combine_pairwise_targets(j, y_c, y_j) where a pass defines its own (both passes do: one decode
// and one light fetch each), all defined by the including pass before this header
// (restir.temporal: the canonical pixel decoded once, last frame's pixels as indices into the
// history; restir.spatial: neighbours as pixel indices; both decoded at each use). Loop-indexed
// private arrays of decoded domains are what lavapipe spills: both passes measured faster
// without them.
#include "shared/reservoir_combine.h"

// Resamples the `count` domains into one finalized reservoir for the canonical pixel.
Reservoir restir_combine(uint count, uint mode, inout uint rng) {
  return reservoir_combine(count, mode, rng);
}

#endif
