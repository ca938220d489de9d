// Resampling MIS weights m_i for combining reservoirs from several domains (pixels or frames),
// one helper per bias-correction mode. Each returns the m_i that reservoir_merge expects; the
// weights of one resampling sum to 1 wherever the canonical pixel's target is non-zero.
//
// Notation: the canonical domain c is the pixel being shaded; neighbours i = 1..k are reused
// reservoirs. conf_i is a domain's confidence (its M); p_i(y) its target function at sample y.
#ifndef LANTERN_SHARED_RESERVOIR_MIS_H
#define LANTERN_SHARED_RESERVOIR_MIS_H

#include "shared/common_math.h"
#include "shared/lang.h"

LANTERN_BEGIN_SHARED

// Bias-correction modes (the `bias_correction` setting).
LANTERN_CONST uint kBiasCorrectionNone = 0u;      // 1/M: fast, biased where domains differ
LANTERN_CONST uint kBiasCorrectionBalance = 1u;   // generalized balance heuristic, O(k^2) p̂ evals
LANTERN_CONST uint kBiasCorrectionPairwise = 2u;  // pairwise MIS, O(k) p̂ evals

// Bound on one conf * p̂ product in a denominator (keeps sums of them finite).
LANTERN_CONST float kMaxMisTerm = 1e30f;

// `none`: m_i = conf_i / sum of all confidences (the classic 1/M when each conf is 1). Ignores
// where each domain can produce y, so it is biased when some neighbour's target is zero where
// the canonical one is not.
LANTERN_FUNC float mis_weight_none(float conf_i, float conf_total) {
  return safe_ratio(conf_i, conf_total);
}

// `balance`: m_i(y) = conf_i p_i(y) / sum_j conf_j p_j(y). The caller accumulates the
// denominator over every domain (canonical included) at the same y.
LANTERN_FUNC float mis_weight_balance(float conf_i, float p_i_at_y, float denominator) {
  return safe_ratio(conf_i * finite_positive_or_zero(p_i_at_y), denominator);
}

// conf_j * p_j(y), guarded (non-finite or negative factors count as 0) and bounded so that a sum
// of a few hundred terms stays finite.
LANTERN_FUNC float mis_balance_term(float conf_j, float p_j_at_y) {
  return min(finite_positive_or_zero(conf_j) * finite_positive_or_zero(p_j_at_y), kMaxMisTerm);
}

// Number of pairs k as a divisor: at least 1, and 1 for a non-finite k.
LANTERN_FUNC float mis_pair_count(float k) {
  return max(finite_positive_or_zero(k), 1.0f);
}

// `pairwise` (Bitterli 2022; Lin et al. 2022, "Generalized Resampled Importance Sampling"): each
// neighbour i forms a pair with the canonical domain, whose confidence is split over the k pairs,
// and each pair shares 1/k of the total:
//   b_i(y) = conf_i p_i(y) / (conf_i p_i(y) + (conf_c / k) p_c(y))
//   m_i(y_i) = b_i(y_i) / k                 for neighbour i's own sample
//   m_c(y_c) = sum_i (1 - b_i(y_c)) / k     for the canonical sample (m_c = 1 when k = 0)
LANTERN_FUNC float mis_pairwise_b(float conf_i, float p_i_at_y, float conf_c, float p_c_at_y,
                                  float k) {
  float neighbour = mis_balance_term(conf_i, p_i_at_y);
  float canonical = mis_balance_term(conf_c, p_c_at_y) / mis_pair_count(k);
  return safe_ratio(neighbour, neighbour + canonical);
}

// m_i for neighbour i's own sample y_i (p_i_at_y = its stored target, p_c_at_y = p̂_c(y_i)).
LANTERN_FUNC float mis_pairwise_neighbour(float conf_i, float p_i_at_y, float conf_c,
                                          float p_c_at_y, float k) {
  return mis_pairwise_b(conf_i, p_i_at_y, conf_c, p_c_at_y, k) / mis_pair_count(k);
}

// Neighbour i's share of the canonical sample's weight m_c(y_c): sum it over i = 1..k
// (p_i_at_y = p̂_i(y_c), p_c_at_y = p̂_c(y_c)). Start the sum at mis_pairwise_canonical_init(k).
LANTERN_FUNC float mis_pairwise_canonical_term(float conf_i, float p_i_at_y, float conf_c,
                                               float p_c_at_y, float k) {
  float neighbour = mis_balance_term(conf_i, p_i_at_y);
  float canonical = mis_balance_term(conf_c, p_c_at_y) / mis_pair_count(k);
  return neighbour + canonical > 0.0f ? (canonical / (neighbour + canonical)) / mis_pair_count(k)
                                      : 1.0f / mis_pair_count(k);
}

LANTERN_FUNC float mis_pairwise_canonical_init(float k) {
  return finite_positive_or_zero(k) > 0.0f ? 0.0f : 1.0f;
}

LANTERN_END_SHARED

#endif
