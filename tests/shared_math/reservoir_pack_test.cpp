// PackedReservoir round trip: every field comes back within its documented quantisation.
#include "shared/reservoir_pack.h"

#include <gtest/gtest.h>

#include <cmath>

#include "shared/rng.h"

namespace lantern::gpu {
namespace {

TEST(ReservoirPack, RoundTripWithinQuantisation) {
  uint rng = rng_init(uvec2(8u, 8u), 0u, 5u, 0u);
  for (int i = 0; i < 100000; ++i) {
    Reservoir r = reservoir_empty();
    r.selected = light_sample_make(rng_next_uint(rng) % 5000000u, rng_next_vec2(rng),
                                   std::exp2(rng_next_float(rng) * 30.0f - 14.0f));  // 6e-5..6.5e4
    r.W = std::exp2(rng_next_float(rng) * 60.0f - 30.0f);
    r.M = float(rng_next_uint(rng) % 2000u);
    r.weight_sum = r.W * r.selected.target_pdf;
    Reservoir u = reservoir_unpack(reservoir_pack(r));
    ASSERT_EQ(u.selected.light_index, r.selected.light_index);
    ASSERT_LE(std::abs(u.selected.u - r.selected.u), 0.5f / 65535.0f + 1e-7f);
    ASSERT_LE(std::abs(u.selected.v - r.selected.v), 0.5f / 65535.0f + 1e-7f);
    ASSERT_EQ(u.W, r.W);
    ASSERT_EQ(u.M, r.M);
    float rel = std::abs(u.selected.target_pdf - r.selected.target_pdf) / r.selected.target_pdf;
    ASSERT_LE(rel, std::exp2(-11.0f)) << r.selected.target_pdf;
    // Re-finalising an unpacked reservoir gives back its W.
    Reservoir again = u;
    reservoir_finalize(again);
    ASSERT_NEAR(again.W, u.W, 1e-3f * u.W);
  }
}

TEST(ReservoirPack, SixteenBytes) {
  EXPECT_EQ(sizeof(PackedReservoir), 16u);
}

TEST(ReservoirPack, EdgeValues) {
  Reservoir r = reservoir_empty();
  r.selected = light_sample_make(7u, vec2(0.0f, 1.0f), 1e-9f);  // below the smallest half
  r.W = 2.0f;
  r.M = 70000.0f;  // beyond 16 bits
  Reservoir u = reservoir_unpack(reservoir_pack(r));
  EXPECT_GT(u.selected.target_pdf, 0.0f) << "a positive p̂ must stay positive";
  EXPECT_EQ(u.M, 65535.0f);
  EXPECT_EQ(u.selected.u, 0.0f);
  EXPECT_EQ(u.selected.v, 1.0f);

  r.selected.target_pdf = 1e9f;  // beyond the largest half
  u = reservoir_unpack(reservoir_pack(r));
  EXPECT_EQ(u.selected.target_pdf, 65504.0f);

  Reservoir empty = reservoir_unpack(reservoir_pack(reservoir_empty()));
  EXPECT_EQ(empty.selected.light_index, kInvalidLight);
  EXPECT_EQ(empty.W, 0.0f);
  EXPECT_FALSE(reservoir_has_sample(empty));
}

}  // namespace
}  // namespace lantern::gpu
