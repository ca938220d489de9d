// NaN, Inf and negative inputs never produce a non-finite reservoir: a fuzz over update, merge,
// finalize, M capping and pack/unpack with hostile values mixed into ordinary ones, and raw stored
// words (what a corrupted or uninitialised reservoir buffer holds) unpacked.
#include <gtest/gtest.h>

#include <cstring>
#include <limits>
#include <vector>

#include "shared/reservoir.h"
#include "shared/reservoir_mis.h"
#include "shared/reservoir_pack.h"
#include "shared/rng.h"

namespace lantern::gpu {
namespace {

const std::vector<float>& hostile_values() {
  static const std::vector<float> values = {std::numeric_limits<float>::quiet_NaN(),
                                            std::numeric_limits<float>::infinity(),
                                            -std::numeric_limits<float>::infinity(),
                                            -1.0f,
                                            -0.0f,
                                            0.0f,
                                            std::numeric_limits<float>::max(),
                                            std::numeric_limits<float>::denorm_min(),
                                            std::numeric_limits<float>::min(),
                                            1e30f,
                                            1e-30f,
                                            1.0f,
                                            0.5f};
  return values;
}

// A value drawn half the time from the hostile list, otherwise an ordinary positive number.
float pick(uint& rng) {
  const std::vector<float>& hostile = hostile_values();
  if (rng_next_float(rng) < 0.5f) return rng_next_float(rng) * 4.0f;
  return hostile[min(uint(rng_next_float(rng) * float(hostile.size())), uint(hostile.size()) - 1u)];
}

::testing::AssertionResult finite_state(const Reservoir& r) {
  if (!is_finite(r.weight_sum) || r.weight_sum < 0.0f)
    return ::testing::AssertionFailure() << "weight_sum " << r.weight_sum;
  if (!is_finite(r.W) || r.W < 0.0f) return ::testing::AssertionFailure() << "W " << r.W;
  if (!is_finite(r.M) || r.M < 0.0f) return ::testing::AssertionFailure() << "M " << r.M;
  if (!is_finite(r.selected.target_pdf) || r.selected.target_pdf < 0.0f)
    return ::testing::AssertionFailure() << "target_pdf " << r.selected.target_pdf;
  return ::testing::AssertionSuccess();
}

TEST(ReservoirGuard, IsFiniteClassifiesSpecialValues) {
  EXPECT_FALSE(is_finite(std::numeric_limits<float>::quiet_NaN()));
  EXPECT_FALSE(is_finite(std::numeric_limits<float>::infinity()));
  EXPECT_FALSE(is_finite(-std::numeric_limits<float>::infinity()));
  EXPECT_TRUE(is_finite(std::numeric_limits<float>::max()));
  EXPECT_TRUE(is_finite(-0.0f));
  EXPECT_EQ(finite_positive_or_zero(-2.0f), 0.0f);
  EXPECT_EQ(safe_ratio(1.0f, 0.0f), 0.0f);
  EXPECT_EQ(safe_ratio(std::numeric_limits<float>::max(), 1e-30f), 0.0f);
}

TEST(ReservoirGuard, HostileInputsKeepStateFinite) {
  uint rng = rng_init(uvec2(4u, 2u), 0u, 31337u, 0u);
  for (int trial = 0; trial < 20000; ++trial) {
    Reservoir r = reservoir_empty();
    for (int i = 0; i < 8; ++i) {
      LightSample s = light_sample_make(uint(i), vec2(pick(rng), pick(rng)), pick(rng));
      ASSERT_TRUE(is_finite(s.u) && s.u >= 0.0f && s.u <= 1.0f && is_finite(s.v)) << s.u;
      reservoir_update(r, s, pick(rng), pick(rng));
      ASSERT_TRUE(finite_state(r)) << "after update " << i << " of trial " << trial;
    }
    Reservoir other = reservoir_empty();
    other.selected = light_sample_make(99u, vec2(0.5f), pick(rng));
    other.W = pick(rng);
    other.M = pick(rng);
    other.weight_sum = pick(rng);
    float m = mis_pairwise_neighbour(pick(rng), pick(rng), pick(rng), pick(rng), pick(rng));
    ASSERT_TRUE(is_finite(m) && m >= 0.0f && m <= 1.0f) << "pairwise m " << m;
    float mb = mis_weight_balance(pick(rng), pick(rng), pick(rng));
    ASSERT_TRUE(is_finite(mb) && mb >= 0.0f) << "balance m " << mb;
    reservoir_merge(r, other, pick(rng) * m, pick(rng), pick(rng));
    ASSERT_TRUE(finite_state(r)) << "after merge, trial " << trial;
    reservoir_finalize(r);
    ASSERT_TRUE(finite_state(r)) << "after finalize, trial " << trial;
    reservoir_cap_m(r, pick(rng));
    ASSERT_TRUE(finite_state(r)) << "after cap, trial " << trial;
    Reservoir round_trip = reservoir_unpack(reservoir_pack(r));
    ASSERT_TRUE(finite_state(round_trip)) << "after pack, trial " << trial;
  }
}

TEST(ReservoirGuard, HugeWeightsDoNotOverflowTheSum) {
  Reservoir r = reservoir_empty();
  for (int i = 0; i < 1000; ++i)
    reservoir_update(r, light_sample_make(uint(i), vec2(0.5f), 1.0f),
                     std::numeric_limits<float>::max(), 0.5f);
  EXPECT_TRUE(is_finite(r.weight_sum));
  reservoir_finalize(r);
  EXPECT_TRUE(finite_state(r));
  EXPECT_GT(r.W, 0.0f);
}

TEST(ReservoirGuard, ZeroTargetAtTheSelectedSampleEmptiesTheReservoir) {
  Reservoir r = reservoir_empty();
  reservoir_update(r, light_sample_make(3u, vec2(0.5f), 0.0f), 1.0f, 0.1f);
  reservoir_finalize(r);
  EXPECT_EQ(r.W, 0.0f);
  EXPECT_FALSE(reservoir_has_sample(r));
}

// Raw words with NaN/Inf/negative W (any light index, M and p̂) unpack to an empty reservoir:
// no sample, W and weight_sum 0, everything finite.
TEST(ReservoirGuard, RawNonFiniteWordsUnpackToEmpty) {
  const float w_values[] = {std::numeric_limits<float>::quiet_NaN(),
                            -std::numeric_limits<float>::quiet_NaN(),
                            std::numeric_limits<float>::signaling_NaN(),
                            std::numeric_limits<float>::infinity(),
                            -std::numeric_limits<float>::infinity(),
                            -1.0f,
                            -std::numeric_limits<float>::denorm_min()};
  const uint light_ages[] = {0u, 7u, (3u << 24u) | 12345u, kPackedNoLight, 0x7f800000u,
                             0xffffffffu};
  const uint m_targets[] = {0u, 1u | (0x3c00u << 16u), 0xffffu | (0x7c00u << 16u),
                            5u | (0x7e00u << 16u), 0xffffffffu};
  for (const float w : w_values)
    for (const uint light_age : light_ages)
      for (const uint m_target : m_targets) {
        PackedReservoir p;
        p.light_age = light_age;
        p.uv = 0x8000ffffu;
        p.W = w;
        p.m_target = m_target;
        const Reservoir r = reservoir_unpack(p);
        ASSERT_FALSE(reservoir_has_sample(r)) << "W " << w << " light_age " << light_age;
        ASSERT_EQ(r.W, 0.0f) << "W " << w;
        ASSERT_EQ(r.weight_sum, 0.0f) << "W " << w;
        ASSERT_TRUE(finite_state(r)) << "W " << w << " m_target " << m_target;
        ASSERT_TRUE(is_finite(r.selected.u) && is_finite(r.selected.v));
      }
}

// Every word all ones or all the bits of +Inf / NaN: empty and finite.
TEST(ReservoirGuard, RawAllOnesAndInfWordsUnpackToEmpty) {
  for (const uint word : {0xffffffffu, 0x7f800000u, 0x7fc00000u, 0xff800000u}) {
    PackedReservoir p;
    p.light_age = word;
    p.uv = word;
    std::memcpy(&p.W, &word, sizeof(float));
    p.m_target = word;
    const Reservoir r = reservoir_unpack(p);
    EXPECT_FALSE(reservoir_has_sample(r)) << std::hex << word;
    EXPECT_EQ(r.W, 0.0f) << std::hex << word;
    EXPECT_EQ(r.weight_sum, 0.0f) << std::hex << word;
    EXPECT_TRUE(finite_state(r)) << std::hex << word;
  }
}

// A finite W with a NaN/Inf/negative half p̂ (bits no reservoir_pack writes): p̂ reads 0, so the
// unpacked weight_sum is 0 and nothing non-finite enters a merge.
TEST(ReservoirGuard, RawNonFiniteTargetPdfUnpacksToZero) {
  for (const uint half : {0x7c00u, 0xfc00u, 0x7e00u, 0x7fffu, 0xffffu, 0xbc00u}) {
    PackedReservoir p;
    p.light_age = 7u;
    p.uv = 0u;
    p.W = 2.0f;
    p.m_target = 4u | (half << 16u);
    const Reservoir r = reservoir_unpack(p);
    EXPECT_EQ(r.selected.target_pdf, 0.0f) << std::hex << half;
    EXPECT_EQ(r.weight_sum, 0.0f) << std::hex << half;
    EXPECT_TRUE(finite_state(r)) << std::hex << half;
  }
}

}  // namespace
}  // namespace lantern::gpu
