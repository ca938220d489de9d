// Combining reservoirs from several domains (restir.temporal: pixel + its history; restir.spatial:
// pixel + k neighbours) with the resampling MIS weights of the bias-correction mode
// (shared/reservoir_mis.h). Domain 0 is the canonical pixel; the caller fills g_reservoirs and
// g_points (finalized reservoirs, decoded surfaces) and calls restir_combine.
#ifndef LANTERN_RESTIR_REUSE_GLSL
#define LANTERN_RESTIR_REUSE_GLSL

#include "restir/restir_common.glsl"

const uint kRestirMaxDomains = kRestirMaxNeighbours + 1u;

Reservoir g_reservoirs[kRestirMaxDomains];
ShadingPoint g_points[kRestirMaxDomains];

// m_j(y_j) for domain j's own sample; p_c = p̂ of y_j at the canonical pixel.
float restir_mis_weight(uint j, uint count, uint mode, float p_c, float m_total) {
  LightSample y = g_reservoirs[j].selected;
  float k = float(count - 1u);
  if (mode == kBiasCorrectionNone) {
    return mis_weight_none(g_reservoirs[j].M, m_total);
  }
  if (mode == kBiasCorrectionBalance) {
    float denominator = 0.0;
    float p_j = 0.0;
    for (uint l = 0u; l < count; ++l) {
      float p_l = l == 0u ? p_c : restir_target(g_points[l], y);
      if (l == j) p_j = p_l;
      denominator += mis_balance_term(g_reservoirs[l].M, p_l);
    }
    return mis_weight_balance(g_reservoirs[j].M, p_j, denominator);
  }
  // Pairwise.
  float m_c = g_reservoirs[0].M;
  if (j == 0u) {
    float m = mis_pairwise_canonical_init(k);
    for (uint i = 1u; i < count; ++i) {
      m += mis_pairwise_canonical_term(g_reservoirs[i].M, restir_target(g_points[i], y), m_c, p_c, k);
    }
    return m;
  }
  return mis_pairwise_neighbour(g_reservoirs[j].M, restir_target(g_points[j], y), m_c, p_c, k);
}

// Resamples the `count` domains into one finalized reservoir for the canonical pixel.
Reservoir restir_combine(uint count, uint mode, inout uint rng) {
  float m_total = 0.0;
  for (uint j = 0u; j < count; ++j) m_total += g_reservoirs[j].M;
  Reservoir out_r = reservoir_empty();
  for (uint j = 0u; j < count; ++j) {
    float u = rng_next_float(rng);
    float p_c = 0.0;
    float m = 0.0;
    if (reservoir_has_sample(g_reservoirs[j])) {
      p_c = restir_target(g_points[0], g_reservoirs[j].selected);
      if (p_c > 0.0) m = restir_mis_weight(j, count, mode, p_c, m_total);
    }
    reservoir_merge(out_r, g_reservoirs[j], m, p_c, u);
  }
  reservoir_finalize(out_r);
  return out_r;
}

#endif
