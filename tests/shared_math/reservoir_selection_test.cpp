// Reservoir selection statistics: streaming picks each candidate with probability proportional
// to its weight, and merging two reservoirs is equivalent to one reservoir over the union.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "shared/reservoir.h"
#include "shared/rng.h"
#include "statistics.h"

namespace lantern::gpu {
namespace {

constexpr int kTrials = 1000000;

std::vector<double> normalised(const std::vector<float>& weights) {
  double sum = 0.0;
  for (float w : weights) sum += w;
  std::vector<double> p;
  for (float w : weights) p.push_back(w / sum);
  return p;
}

// Streams candidates [first, first + count) with the given weights; candidate i's target is
// targets[i] and its index is its light index.
Reservoir stream(const std::vector<float>& weights, const std::vector<float>& targets, uint first,
                 uint count, uint& rng) {
  Reservoir r = reservoir_empty();
  for (uint i = first; i < first + count; ++i) {
    reservoir_update(r, light_sample_make(i, vec2(0.25f, 0.75f), targets[i]), weights[i],
                     rng_next_float(rng));
  }
  return r;
}

TEST(ReservoirSelection, FrequenciesMatchWeights) {
  // Weights spanning three orders of magnitude, one zero (must never be chosen).
  const std::vector<float> weights = {1.0f, 0.5f, 3.0f, 0.0f,  0.01f, 2.5f, 7.0f, 0.2f,
                                      1.5f, 4.0f, 0.7f, 0.05f, 6.0f,  1.0f, 2.0f, 0.3f};
  const std::vector<float> targets(weights.size(), 1.0f);
  uint rng = rng_init(uvec2(1u, 2u), 0u, 12345u, 0u);
  std::vector<std::uint64_t> counts(weights.size(), 0);
  for (int t = 0; t < kTrials; ++t) {
    Reservoir r = stream(weights, targets, 0u, uint(weights.size()), rng);
    ASSERT_NE(r.selected.light_index, kInvalidLight);
    counts[r.selected.light_index]++;
  }
  EXPECT_EQ(counts[3], 0u) << "a zero-weight candidate was selected";
  int dof = 0;
  double chi2 = test::chi_square(counts, normalised(weights), dof);
  double critical = test::chi_square_critical(dof, test::kZ1e3);
  std::printf("selection: chi2 %.2f (dof %d, p=1e-3 critical %.2f)\n", chi2, dof, critical);
  EXPECT_LT(chi2, critical);
}

TEST(ReservoirSelection, MergeOfTwoEqualsOneOverTheUnion) {
  // Candidates 0..5 go to reservoir A, 6..13 to B; both share one target function (same pixel),
  // so merging with m = 1 at the stored target must reproduce streaming all 14 at once.
  const std::vector<float> weights = {0.3f, 2.0f, 1.0f,  0.1f, 5.0f, 0.6f, 1.2f,
                                      3.3f, 0.8f, 0.05f, 2.2f, 4.0f, 0.4f, 1.7f};
  const std::vector<float> targets = {0.5f, 1.0f, 2.0f, 0.25f, 4.0f, 1.5f, 0.3f,
                                      2.5f, 0.9f, 0.1f, 3.0f,  6.0f, 0.7f, 1.1f};
  const uint a_count = 6u;
  const uint b_count = uint(weights.size()) - a_count;
  double union_sum = 0.0;
  for (float w : weights) union_sum += w;

  uint rng = rng_init(uvec2(9u, 9u), 0u, 777u, 0u);
  std::vector<std::uint64_t> merged_counts(weights.size(), 0);
  std::vector<std::uint64_t> union_counts(weights.size(), 0);
  for (int t = 0; t < kTrials; ++t) {
    Reservoir a = stream(weights, targets, 0u, a_count, rng);
    Reservoir b = stream(weights, targets, a_count, b_count, rng);
    reservoir_finalize(a);
    reservoir_finalize(b);
    Reservoir merged = reservoir_empty();
    reservoir_merge(merged, a, 1.0f, a.selected.target_pdf, rng_next_float(rng));
    reservoir_merge(merged, b, 1.0f, b.selected.target_pdf, rng_next_float(rng));
    reservoir_finalize(merged);

    Reservoir whole = stream(weights, targets, 0u, uint(weights.size()), rng);
    reservoir_finalize(whole);

    ASSERT_NEAR(merged.weight_sum, union_sum, 1e-5 * union_sum);
    ASSERT_NEAR(whole.weight_sum, union_sum, 1e-5 * union_sum);
    ASSERT_EQ(merged.M, whole.M);
    // Same sample -> same W: W = union weight sum / p̂(y) in both.
    uint y = merged.selected.light_index;
    ASSERT_NEAR(merged.W, union_sum / targets[y], 1e-5 * merged.W);
    merged_counts[y]++;
    union_counts[whole.selected.light_index]++;
  }
  std::vector<double> p = normalised(weights);
  int dof = 0;
  double chi2_merged = test::chi_square(merged_counts, p, dof);
  double chi2_union = test::chi_square(union_counts, p, dof);
  double critical = test::chi_square_critical(dof, test::kZ1e3);
  std::printf("merge: chi2 merged %.2f, union %.2f (dof %d, critical %.2f)\n", chi2_merged,
              chi2_union, dof, critical);
  EXPECT_LT(chi2_merged, critical);
  EXPECT_LT(chi2_union, critical);
}

}  // namespace
}  // namespace lantern::gpu
