// Combining the finalized reservoirs of `count` domains (restir.temporal: the pixel and its
// history; restir.spatial: the pixel and k neighbours) into one for the canonical domain 0, with
// the resampling MIS weights of the bias-correction mode (shared/reservoir_mis.h). Shared by the
// restir.* shaders (restir/restir_reuse.glsl) and the CPU chain tests, so both run this loop.
// The includer defines, before including this header:
//   Reservoir combine_domain_reservoir(uint j)           domain j's finalized reservoir
//   float combine_domain_target(uint j, LightSample y)   p̂ of sample y in domain j
// and may define, with LANTERN_COMBINE_PAIRWISE_TARGETS, a version of
//   vec3 combine_pairwise_targets(uint j, LightSample y_c, LightSample y_j)
//       p̂_j(y_c), p̂_j(y_j) and p̂_c(y_j): pairwise MIS's three evaluations for neighbour j
// that decodes domain j and fetches each light once (else three combine_domain_target calls).
#ifndef LANTERN_SHARED_RESERVOIR_COMBINE_H
#define LANTERN_SHARED_RESERVOIR_COMBINE_H

#include "shared/lang.h"
#include "shared/reservoir.h"
#include "shared/reservoir_mis.h"
#include "shared/rng.h"

LANTERN_BEGIN_SHARED

// m_j(y_j) for domain j's own sample y_j under `none` or `balance` (pairwise MIS has its own
// sweep, reservoir_combine_pairwise); p_c = p̂ of y_j in the canonical domain.
LANTERN_FUNC float reservoir_combine_weight(uint j, uint count, uint mode, float p_c,
                                            float m_total) {
  Reservoir r_j = combine_domain_reservoir(j);
  if (mode == kBiasCorrectionNone) {
    return mis_weight_none(r_j.M, m_total);
  }
  float denominator = 0.0f;
  float p_j = 0.0f;
  for (uint l = 0u; l < count; ++l) {
    float p_l = l == 0u ? p_c : combine_domain_target(l, r_j.selected);
    if (l == j) {
      p_j = p_l;
    }
    denominator += mis_balance_term(combine_domain_reservoir(l).M, p_l);
  }
  return mis_weight_balance(r_j.M, p_j, denominator);
}

#ifndef LANTERN_COMBINE_PAIRWISE_TARGETS
LANTERN_FUNC vec3 combine_pairwise_targets(uint j, LightSample y_c, LightSample y_j) {
  return vec3(combine_domain_target(j, y_c), combine_domain_target(j, y_j),
              combine_domain_target(0u, y_j));
}
#endif

// Pairwise MIS in one sweep over the neighbours: each neighbour's reservoir is read once and its
// three evaluations made together (combine_pairwise_targets), where a per-domain loop (as the one
// below for `none` and `balance`) read the reservoir four times and decoded the domain twice.
// The canonical sample is merged last, when its weight m_c(y_c) is complete; its random number
// is still the first drawn.
LANTERN_FUNC Reservoir reservoir_combine_pairwise(uint count, LANTERN_INOUT(uint) rng) {
  Reservoir canonical = combine_domain_reservoir(0u);
  float u_canonical = rng_next_float(rng);
  float k = float(count - 1u);
  float p_cc = reservoir_has_sample(canonical) ? combine_domain_target(0u, canonical.selected)
                                               : 0.0f;
  float m_canonical = mis_pairwise_canonical_init(k);
  Reservoir out_r = reservoir_empty();
  for (uint j = 1u; j < count; ++j) {
    float u = rng_next_float(rng);
    Reservoir r_j = combine_domain_reservoir(j);
    vec3 p = combine_pairwise_targets(j, canonical.selected, r_j.selected);
    m_canonical += mis_pairwise_canonical_term(r_j.M, p.x, canonical.M, p_cc, k);
    float p_c = reservoir_has_sample(r_j) ? p.z : 0.0f;
    float m = p_c > 0.0f ? mis_pairwise_neighbour(r_j.M, p.y, canonical.M, p_c, k) : 0.0f;
    reservoir_merge(out_r, r_j, m, p_c, u);
  }
  reservoir_merge(out_r, canonical, p_cc > 0.0f ? m_canonical : 0.0f, p_cc, u_canonical);
  reservoir_finalize(out_r);
  return out_r;
}

// Resamples the `count` domains into one finalized reservoir for domain 0 (one random number per
// domain, in domain order).
LANTERN_FUNC Reservoir reservoir_combine(uint count, uint mode, LANTERN_INOUT(uint) rng) {
  if (mode == kBiasCorrectionPairwise) {
    return reservoir_combine_pairwise(count, rng);
  }
  float m_total = 0.0f;
  for (uint j = 0u; j < count; ++j) {
    m_total += combine_domain_reservoir(j).M;
  }
  Reservoir out_r = reservoir_empty();
  for (uint j = 0u; j < count; ++j) {
    float u = rng_next_float(rng);
    Reservoir r_j = combine_domain_reservoir(j);
    float p_c = 0.0f;
    float m = 0.0f;
    if (reservoir_has_sample(r_j)) {
      p_c = combine_domain_target(0u, r_j.selected);
      if (p_c > 0.0f) {
        m = reservoir_combine_weight(j, count, mode, p_c, m_total);
      }
    }
    reservoir_merge(out_r, r_j, m, p_c, u);
  }
  reservoir_finalize(out_r);
  return out_r;
}

LANTERN_END_SHARED

#endif
