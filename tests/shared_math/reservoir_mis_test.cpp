// The resampling MIS weights: for any sample y, the weights the domains would give it sum to 1
// over the domains (balance, pairwise), vanish where a domain's target is zero, and M capping
// only lowers the confidence.
#include "shared/reservoir_mis.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "shared/reservoir.h"
#include "shared/rng.h"

namespace lantern::gpu {
namespace {

// Random confidences and targets at one sample y for a canonical domain (0) and k neighbours;
// about a quarter of the neighbour targets are zero (domains that cannot produce y).
struct Domains {
  std::vector<float> conf;
  std::vector<float> p;  // p_j(y)
};

Domains random_domains(uint k, uint& rng) {
  Domains d;
  for (uint j = 0; j <= k; ++j) {
    d.conf.push_back(1.0f + float(rng_next_uint(rng) % 32u));
    bool zero = j > 0u && rng_next_float(rng) < 0.25f;
    d.p.push_back(zero ? 0.0f : std::exp2(rng_next_float(rng) * 20.0f - 10.0f));
  }
  return d;
}

TEST(ReservoirMis, BalanceWeightsSumToOne) {
  uint rng = rng_init(uvec2(6u), 0u, 50u, 0u);
  for (int trial = 0; trial < 10000; ++trial) {
    Domains d = random_domains(1u + rng_next_uint(rng) % 6u, rng);
    float denominator = 0.0f;
    for (std::size_t j = 0; j < d.p.size(); ++j) denominator += mis_balance_term(d.conf[j], d.p[j]);
    float sum = 0.0f;
    for (std::size_t j = 0; j < d.p.size(); ++j) {
      float m = mis_weight_balance(d.conf[j], d.p[j], denominator);
      if (d.p[j] == 0.0f) {
        ASSERT_EQ(m, 0.0f);
      }
      sum += m;
    }
    ASSERT_NEAR(sum, 1.0f, 1e-5f);
  }
}

TEST(ReservoirMis, PairwiseWeightsSumToOne) {
  uint rng = rng_init(uvec2(7u), 0u, 51u, 0u);
  for (int trial = 0; trial < 10000; ++trial) {
    uint k = rng_next_uint(rng) % 7u;  // includes k = 0: the canonical weight is then 1
    Domains d = random_domains(k, rng);
    float kf = float(k);
    // The weights each domain would give the same y: m_c(y) as the canonical sample, m_i(y) as
    // neighbour i's sample.
    float sum = mis_pairwise_canonical_init(kf);
    for (uint i = 1; i <= k; ++i)
      sum += mis_pairwise_canonical_term(d.conf[i], d.p[i], d.conf[0], d.p[0], kf);
    for (uint i = 1; i <= k; ++i) {
      float m = mis_pairwise_neighbour(d.conf[i], d.p[i], d.conf[0], d.p[0], kf);
      if (d.p[i] == 0.0f) {
        ASSERT_EQ(m, 0.0f);
      }
      sum += m;
    }
    ASSERT_NEAR(sum, 1.0f, 1e-5f) << "k " << k;
  }
}

TEST(ReservoirMis, PairwiseEqualsBalanceForOneNeighbour) {
  // With a single neighbour the pairwise and balance heuristics coincide.
  uint rng = rng_init(uvec2(8u), 0u, 52u, 0u);
  for (int trial = 0; trial < 1000; ++trial) {
    Domains d = random_domains(1u, rng);
    float denominator = mis_balance_term(d.conf[0], d.p[0]) + mis_balance_term(d.conf[1], d.p[1]);
    float balance = mis_weight_balance(d.conf[1], d.p[1], denominator);
    float pairwise = mis_pairwise_neighbour(d.conf[1], d.p[1], d.conf[0], d.p[0], 1.0f);
    ASSERT_NEAR(pairwise, balance, 1e-6f);
  }
}

TEST(ReservoirMis, NoneWeightsByConfidence) {
  EXPECT_FLOAT_EQ(mis_weight_none(4.0f, 16.0f), 0.25f);
  EXPECT_EQ(mis_weight_none(4.0f, 0.0f), 0.0f);
}

TEST(ReservoirMis, CapLowersOnlyM) {
  Reservoir r = reservoir_empty();
  for (uint i = 0; i < 50u; ++i)
    reservoir_update(r, light_sample_make(i, vec2(0.5f), 1.0f), 1.0f, 0.3f);
  reservoir_finalize(r);
  float w = r.W;
  reservoir_cap_m(r, 20.0f);
  EXPECT_EQ(r.M, 20.0f);
  EXPECT_EQ(r.W, w);
  reservoir_cap_m(r, 100.0f);
  EXPECT_EQ(r.M, 20.0f);
}

}  // namespace
}  // namespace lantern::gpu
