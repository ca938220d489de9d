// Combining reservoirs from several domains (restir.temporal: pixel + its history; restir.spatial:
// pixel + k neighbours) with the resampling MIS weights of the bias-correction mode
// (shared/reservoir_combine.h, the loop the CPU chain tests run). Domain 0 is the canonical pixel;
// the caller fills g_reservoirs and g_points (finalized reservoirs, decoded surfaces), or defines
// the domain accessors itself (below), and calls restir_combine.
#ifndef LANTERN_RESTIR_REUSE_GLSL
#define LANTERN_RESTIR_REUSE_GLSL

#include "restir/restir_common.glsl"

const uint kRestirMaxDomains = kRestirMaxNeighbours + 1u;

// The shared combine loop (shared/reservoir_combine.h) reads the domains through
// combine_domain_reservoir(j) and combine_domain_target(j, y). A pass that defines
// RESTIR_REUSE_PASS_DOMAINS provides them itself (restir.spatial: from pixel indices, since a
// private array of decoded points indexed by a loop counter cost lavapipe more than decoding
// again); otherwise the pass fills these arrays.
#ifndef RESTIR_REUSE_PASS_DOMAINS
Reservoir g_reservoirs[kRestirMaxDomains];
ShadingPoint g_points[kRestirMaxDomains];

Reservoir combine_domain_reservoir(uint j) { return g_reservoirs[j]; }
float combine_domain_target(uint j, LightSample y) { return restir_target(g_points[j], y); }
#endif

#include "shared/reservoir_combine.h"

// Resamples the `count` domains into one finalized reservoir for the canonical pixel.
Reservoir restir_combine(uint count, uint mode, inout uint rng) {
  return reservoir_combine(count, mode, rng);
}

#endif
