// OffsetAllocator: alignment, best fit, coalescing, exhaustion and a randomized no-overlap check.
#include "runtime/gpu/offset_allocator.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <stdexcept>
#include <vector>

namespace lantern::runtime {
namespace {

TEST(OffsetAllocator, HonoursAlignment) {
  OffsetAllocator a(1024);
  const auto first = a.allocate(3, 1);
  const auto second = a.allocate(16, 256);
  ASSERT_TRUE(first && second);
  EXPECT_EQ(*first, 0u);
  EXPECT_EQ(*second % 256, 0u);
  EXPECT_GE(*second, 3u);
  EXPECT_EQ(a.used(), 19u);
}

TEST(OffsetAllocator, BestFitPicksTheSmallestHole) {
  OffsetAllocator a(1000);
  const auto x = a.allocate(100, 1);         // [0,100)
  const auto gap_big = a.allocate(300, 1);   // [100,400)
  const auto y = a.allocate(100, 1);         // [400,500)
  const auto gap_small = a.allocate(50, 1);  // [500,550)
  const auto z = a.allocate(100, 1);         // [550,650)
  ASSERT_TRUE(x && gap_big && y && gap_small && z);
  a.free(*gap_big);
  a.free(*gap_small);
  const auto fit = a.allocate(40, 1);
  ASSERT_TRUE(fit);
  EXPECT_EQ(*fit, *gap_small)
      << "a 40-byte request belongs in the 50-byte hole, not the 300-byte one";
}

TEST(OffsetAllocator, CoalescesNeighboursOnFree) {
  OffsetAllocator a(300);
  const auto p = a.allocate(100, 1);
  const auto q = a.allocate(100, 1);
  const auto r = a.allocate(100, 1);
  ASSERT_TRUE(p && q && r);
  EXPECT_FALSE(a.allocate(1, 1)) << "full";
  a.free(*p);
  a.free(*r);
  EXPECT_EQ(a.free_range_count(), 2u);
  EXPECT_FALSE(a.allocate(150, 1)) << "two separate 100-byte holes cannot hold 150";
  a.free(*q);
  EXPECT_EQ(a.free_range_count(), 1u);
  EXPECT_EQ(a.largest_free_range(), 300u);
  EXPECT_TRUE(a.empty());
  EXPECT_TRUE(a.allocate(300, 1));
}

TEST(OffsetAllocator, RejectsBadUse) {
  OffsetAllocator a(64);
  EXPECT_THROW(a.allocate(8, 3), std::logic_error);
  EXPECT_THROW(a.free(12), std::logic_error);
  EXPECT_FALSE(a.allocate(65, 1));
}

TEST(OffsetAllocator, RandomizedAllocationsNeverOverlap) {
  constexpr std::uint64_t kCapacity = 1 << 20;
  OffsetAllocator a(kCapacity);
  std::mt19937 rng(7);
  struct Live {
    std::uint64_t offset, size;
  };
  std::vector<Live> live;
  for (int step = 0; step < 20000; ++step) {
    if (live.empty() || rng() % 3 != 0) {
      const std::uint64_t size = 1 + rng() % 4096;
      const std::uint64_t alignment = std::uint64_t{1} << (rng() % 9);
      if (auto offset = a.allocate(size, alignment)) {
        ASSERT_EQ(*offset % alignment, 0u);
        ASSERT_LE(*offset + size, kCapacity);
        live.push_back({*offset, size});
      }
    } else {
      const std::size_t i = rng() % live.size();
      a.free(live[i].offset);
      live.erase(live.begin() + static_cast<std::ptrdiff_t>(i));
    }
  }
  std::sort(live.begin(), live.end(),
            [](const Live& l, const Live& r) { return l.offset < r.offset; });
  std::uint64_t used = 0;
  for (std::size_t i = 0; i < live.size(); ++i) {
    used += live[i].size;
    if (i > 0) {
      ASSERT_LE(live[i - 1].offset + live[i - 1].size, live[i].offset)
          << "overlap at " << live[i].offset;
    }
  }
  EXPECT_EQ(a.used(), used);
  for (const Live& l : live) a.free(l.offset);
  EXPECT_EQ(a.free_range_count(), 1u);
  EXPECT_EQ(a.largest_free_range(), kCapacity);
}

}  // namespace
}  // namespace lantern::runtime
