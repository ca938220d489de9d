// The shared PCG RNG: floats in [0,1) with uniform distribution, deterministic, and distinct
// streams for different pixels, frames, seeds and passes.
#include "shared/rng.h"

#include <gtest/gtest.h>

#include <set>

#include "statistics.h"

namespace lantern::gpu {
namespace {

TEST(SharedRng, FloatsAreInUnitIntervalAndUniform) {
  uint state = rng_init(uvec2(17u, 5u), 2u, 1u, 0u);
  constexpr int kBins = 64;
  constexpr int kDraws = 1000000;
  std::vector<std::uint64_t> counts(kBins, 0);
  for (int i = 0; i < kDraws; ++i) {
    float x = rng_next_float(state);
    ASSERT_GE(x, 0.0f);
    ASSERT_LT(x, 1.0f);
    counts[static_cast<std::size_t>(x * kBins)]++;
  }
  int dof = 0;
  double chi2 = test::chi_square(counts, std::vector<double>(kBins, 1.0 / kBins), dof);
  EXPECT_LT(chi2, test::chi_square_critical(dof, test::kZ1e3)) << "dof " << dof;
}

TEST(SharedRng, LargestDrawStaysBelowOne) {
  // 0xffffffff >> 8 is the largest 24-bit value: the float must still be < 1.
  EXPECT_LT(float(0xffffffffu >> 8u) * (1.0f / 16777216.0f), 1.0f);
}

TEST(SharedRng, SameInputsSameSequence) {
  uint a = rng_init(uvec2(3u, 4u), 10u, 7u, 2u);
  uint b = rng_init(uvec2(3u, 4u), 10u, 7u, 2u);
  for (int i = 0; i < 100; ++i) EXPECT_EQ(rng_next_uint(a), rng_next_uint(b));
}

TEST(SharedRng, StreamsDifferAcrossPixelFrameSeedAndPass) {
  std::set<uint> first_draws;
  int streams = 0;
  for (uint x = 0; x < 16u; ++x)
    for (uint y = 0; y < 16u; ++y)
      for (uint frame = 0; frame < 4u; ++frame)
        for (uint pass = 0; pass < 4u; ++pass) {
          uint s = rng_init(uvec2(x, y), frame, 1u, pass);
          first_draws.insert(rng_next_uint(s));
          ++streams;
        }
  // 4096 streams of 32-bit first draws: a collision or two is possible by chance, no more.
  EXPECT_GE(first_draws.size(), static_cast<std::size_t>(streams - 2));
  uint seed1 = rng_init(uvec2(0u), 0u, 1u, 0u);
  uint seed2 = rng_init(uvec2(0u), 0u, 2u, 0u);
  EXPECT_NE(rng_next_uint(seed1), rng_next_uint(seed2));
}

}  // namespace
}  // namespace lantern::gpu
