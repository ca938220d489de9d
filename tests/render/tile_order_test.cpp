// The shuffled tile order of the per-pixel passes (lighting/frame/tile_order.h): g -> g * stride
// mod count visits every tile exactly once, for every count a frame size can give.
#include <gtest/gtest.h>

#include <vector>

#include "lighting/frame/tile_order.h"

namespace lantern::lighting {
namespace {

TEST(TileOrder, CountCoversTheImage) {
  EXPECT_EQ(tile_count(160, 90, 8), 20u * 12u);
  EXPECT_EQ(tile_count(1, 1, 8), 1u);
  EXPECT_EQ(tile_count(64, 64, 8), 64u);
  EXPECT_EQ(tile_count(65, 64, 16), 5u * 4u);
}

TEST(TileOrder, StrideIsAPermutationAndScatters) {
  for (std::uint32_t count = 1; count <= 5000; ++count) {
    const std::uint32_t stride = tile_stride(count);
    std::vector<bool> seen(count, false);
    for (std::uint64_t g = 0; g < count; ++g) {
      const auto tile = static_cast<std::uint32_t>(g * stride % count);
      ASSERT_FALSE(seen[tile]) << "count " << count << " stride " << stride;
      seen[tile] = true;
    }
    if (count >= 16) {
      EXPECT_GT(stride, count / 2) << "neighbouring workgroups must land far apart";
    }
  }
  EXPECT_EQ(tile_stride(100000), 1u) << "beyond 65535 the product could overflow";
}

}  // namespace
}  // namespace lantern::lighting
