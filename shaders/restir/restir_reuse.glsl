// Combining reservoirs from several domains (restir.temporal: pixel + its history; restir.spatial:
// pixel + k neighbours) with the resampling MIS weights of the bias-correction mode
// (shared/reservoir_combine.h, the loop the CPU chain tests run). Domain 0 is the canonical pixel;
// the caller fills g_reservoirs and g_points (finalized reservoirs, decoded surfaces) and calls
// restir_combine.
#ifndef LANTERN_RESTIR_REUSE_GLSL
#define LANTERN_RESTIR_REUSE_GLSL

#include "restir/restir_common.glsl"

const uint kRestirMaxDomains = kRestirMaxNeighbours + 1u;

Reservoir g_reservoirs[kRestirMaxDomains];
ShadingPoint g_points[kRestirMaxDomains];

// The shared combine loop (shared/reservoir_combine.h) reads the domains through these.
Reservoir combine_domain_reservoir(uint j) { return g_reservoirs[j]; }
float combine_domain_target(uint j, LightSample y) { return restir_target(g_points[j], y); }

#include "shared/reservoir_combine.h"

// Resamples the `count` domains into one finalized reservoir for the canonical pixel.
Reservoir restir_combine(uint count, uint mode, inout uint rng) {
  return reservoir_combine(count, mode, rng);
}

#endif
