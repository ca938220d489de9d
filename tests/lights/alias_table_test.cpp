// Alias table: exact per-index probabilities (summing the table's slots), sampling frequencies
// by chi-square, zero weights never drawn, bad weights rejected.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "engine/core/error.h"
#include "lighting/lights/alias_table.h"

using lantern::lighting::AliasTable;

namespace {

// The exact probability of each index implied by the table: slot i is picked with 1/n, then keeps
// i with `threshold`, else gives its alias.
std::vector<double> implied_probabilities(const AliasTable& table) {
  const std::size_t n = table.size();
  std::vector<double> p(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const auto& e = table.entries()[i];
    p[i] += e.threshold / static_cast<double>(n);
    p[e.alias] += (1.0 - e.threshold) / static_cast<double>(n);
  }
  return p;
}

std::vector<float> skewed_weights(std::size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> exponent(-4.0f, 4.0f);
  std::vector<float> w(n);
  for (auto& x : w) x = std::pow(10.0f, exponent(rng));  // radiances spanning 10^8
  w[n / 2] = 0.0f;                                        // an emitter with no power
  return w;
}

}  // namespace

TEST(AliasTable, ImpliedProbabilitiesEqualNormalisedWeights) {
  for (std::size_t n : {1u, 2u, 3u, 17u, 1000u}) {
    const std::vector<float> w = skewed_weights(std::max<std::size_t>(n, 2), 7 + n);
    const AliasTable table(w);
    double total = 0;
    for (float x : w) total += x;
    const std::vector<double> p = implied_probabilities(table);
    for (std::size_t i = 0; i < w.size(); ++i) {
      EXPECT_NEAR(p[i], w[i] / total, 1e-6) << "n=" << n << " i=" << i;
      EXPECT_NEAR(table.pdf(i), w[i] / total, 1e-6);
    }
  }
}

TEST(AliasTable, SamplingFrequenciesPassChiSquare) {
  const std::vector<float> w = {1.0f, 2.0f, 3.0f, 0.5f, 10.0f, 0.0f, 4.0f, 0.25f};
  const AliasTable table(w);
  std::mt19937 rng(1234);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const int trials = 1'000'000;
  std::vector<int> counts(w.size(), 0);
  for (int t = 0; t < trials; ++t) ++counts[table.sample(u(rng), u(rng))];
  EXPECT_EQ(counts[5], 0) << "a zero-weight index was drawn";
  double chi2 = 0;
  int dof = -1;
  for (std::size_t i = 0; i < w.size(); ++i) {
    const double expected = trials * table.pdf(i);
    if (expected == 0) continue;
    chi2 += (counts[i] - expected) * (counts[i] - expected) / expected;
    ++dof;
  }
  // 6 degrees of freedom: P(chi2 > 22.46) = 0.001.
  EXPECT_EQ(dof, 6);
  EXPECT_LT(chi2, 22.46);
}

TEST(AliasTable, EdgeOfUnitIntervalStaysInRange) {
  const AliasTable table(std::vector<float>{1.0f, 1.0f, 1.0f});
  EXPECT_LT(table.sample(0.99999994f, 0.99999994f), 3u);
  EXPECT_LT(table.sample(0.0f, 0.0f), 3u);
}

TEST(AliasTable, RejectsBadWeights) {
  EXPECT_THROW(AliasTable(std::vector<float>{}), lantern::InputError);
  EXPECT_THROW(AliasTable(std::vector<float>{0.0f, 0.0f}), lantern::InputError);
  EXPECT_THROW(AliasTable(std::vector<float>{1.0f, -1.0f}), lantern::InputError);
  EXPECT_THROW(AliasTable(std::vector<float>{1.0f, NAN}), lantern::InputError);
  EXPECT_THROW(AliasTable(std::vector<float>{INFINITY}), lantern::InputError);
}
