// The tile orders of the per-pixel passes (lighting/frame/tile_order.h, shared/pixel_groups.h's
// pixel_tile_origin): g -> g * stride mod count, and the interleaved bands of tile rows the
// reuse passes walk on CPU devices, visit every tile exactly once for every frame size and tile
// shape (8x8, the CPU's rows); each thread's contiguous run of workgroups walks its own band of
// rows. And restir.temporal's history permutation (restir_permuted_history_pixel): a one-pixel
// move that is its own inverse. And the workgroup shape the per-pixel passes take per device
// (pixel_group_constants).
#include <gtest/gtest.h>
#include <sched.h>

#include <algorithm>
#include <cstdlib>
#include <set>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "lighting/frame/tile_order.h"
#include "shared/pixel_groups.h"
#include "shared/restir.h"

namespace lantern::lighting {
namespace {

// Every frame word moves every pixel by one pixel (horizontally, vertically or diagonally: one of
// the three for the whole frame, the sign by the pixel's place in its 2x2 block) and is an
// involution, hence a permutation of the grid: no history reservoir seeds two pixels. Over
// frames all three directions come up.
TEST(TileOrder, HistoryPermutationMovesEveryPixelOnceByOnePixel) {
  std::set<std::pair<int, int>> directions;
  for (std::uint32_t f = 0; f < 64; ++f) {
    const std::uint32_t word = f * 0x9e3779b9u + (f >> 3);
    for (int y = -3; y < 13; ++y) {
      for (int x = -3; x < 13; ++x) {
        const glm::ivec2 p(x, y);
        const glm::ivec2 q = gpu::restir_permuted_history_pixel(p, word);
        const glm::ivec2 d = q - p;
        ASSERT_LE(std::abs(d.x), 1) << "word " << word << " pixel " << x << "," << y;
        ASSERT_LE(std::abs(d.y), 1) << "word " << word << " pixel " << x << "," << y;
        ASSERT_NE(d, glm::ivec2(0)) << "word " << word << " pixel " << x << "," << y;
        ASSERT_EQ(gpu::restir_permuted_history_pixel(q, word), p)
            << "word " << word << " pixel " << x << "," << y << ": not its own inverse";
        directions.insert({std::abs(d.x), std::abs(d.y)});
      }
    }
  }
  EXPECT_EQ(directions, (std::set<std::pair<int, int>>{{1, 0}, {0, 1}, {1, 1}}));
}

TEST(TileOrder, CountCoversTheImage) {
  EXPECT_EQ(tile_count(160, 90, {8, 8}), 20u * 12u);
  EXPECT_EQ(tile_count(1, 1, {8, 8}), 1u);
  EXPECT_EQ(tile_count(64, 64, {8, 8}), 64u);
  EXPECT_EQ(tile_count(65, 64, {16, 16}), 5u * 4u);
  EXPECT_EQ(tile_count(160, 90, {64, 1}), 3u * 90u);
  EXPECT_EQ(tile_count(320, 180, {64, 1}), 5u * 180u);
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

TEST(TileOrder, BandsArePermutationsAndEachRunWalksItsBand) {
  for (const glm::uvec2 t : {glm::uvec2(8, 8), glm::uvec2(64, 1), glm::uvec2(32, 2)}) {
    for (const auto& [w, h] : {std::pair{320u, 180u}, {640u, 360u}, {160u, 90u}, {8u, 8u},
                               {9u, 200u}, {1u, 1u}, {1280u, 720u}, {95u, 53u}}) {
      const std::uint32_t tiles_x = (w + t.x - 1) / t.x, tiles_y = (h + t.y - 1) / t.y;
      const std::uint32_t count = tiles_x * tiles_y;
      ASSERT_EQ(count, tile_count(w, h, t));
      for (std::uint32_t bands : {0u, 1u, 2u, 3u, 4u, 7u, 16u, 64u}) {
        std::vector<bool> seen(count, false);
        for (std::uint32_t g = 0; g < count; ++g) {
          const glm::uvec2 o = gpu::pixel_tile_origin(g, tile_stride(count), bands, {w, h}, t);
          ASSERT_EQ(o.x % t.x, 0u);
          ASSERT_EQ(o.y % t.y, 0u);
          ASSERT_LT(o.x, w);
          ASSERT_LT(o.y, h);
          const std::uint32_t tile = (o.y / t.y) * tiles_x + o.x / t.x;
          ASSERT_FALSE(seen[tile]) << w << "x" << h << " bands " << bands << " group " << g;
          seen[tile] = true;
          if (bands > 0 && g > 0 && g % tiles_x != 0) {
            const glm::uvec2 before =
                gpu::pixel_tile_origin(g - 1, tile_stride(count), bands, {w, h}, t);
            EXPECT_EQ(before + glm::uvec2(t.x, 0), o) << "consecutive workgroups lie side by side";
          }
        }
      }
    }
  }
  // 2 threads over 320x180 in 8x8 tiles (40 x 23): the first run of rows is the even rows, the
  // second the odd ones, so each thread spans the image's height.
  std::set<std::uint32_t> first, second;
  const std::uint32_t rows = 23, cols = 40;
  for (std::uint32_t g = 0; g < rows * cols; ++g) {
    const std::uint32_t row = gpu::pixel_tile_origin(g, 1, 2, {320, 180}, {8, 8}).y / 8;
    (g < 12 * cols ? first : second).insert(row);
  }
  for (std::uint32_t r : first) EXPECT_EQ(r % 2, 0u) << r;
  for (std::uint32_t r : second) EXPECT_EQ(r % 2, 1u) << r;
  EXPECT_EQ(first.size(), 12u);
  EXPECT_EQ(second.size(), 11u);
}

TEST(TileOrder, BandsFollowTheCpuDevicesThreads) {
  EXPECT_EQ(tile_bands(false), 0u) << "GPUs keep the shuffle";
  const char* saved = std::getenv("LP_NUM_THREADS");
  const std::string restore = saved != nullptr ? saved : "";
  setenv("LP_NUM_THREADS", "3", 1);
  EXPECT_EQ(tile_bands(true), 3u);
  setenv("LP_NUM_THREADS", "0x10", 1);
  EXPECT_EQ(tile_bands(true), 16u) << "read as llvmpipe reads it (any base)";
  setenv("LP_NUM_THREADS", "1000", 1);
  EXPECT_EQ(tile_bands(true), 32u) << "llvmpipe runs at most 32 threads";
  setenv("LP_NUM_THREADS", "0", 1);
  EXPECT_EQ(tile_bands(true), 1u) << "lavapipe runs a dispatch on one thread";
  unsetenv("LP_NUM_THREADS");
  cpu_set_t affinity;
  ASSERT_EQ(sched_getaffinity(0, sizeof(affinity), &affinity), 0);
  const auto usable = static_cast<std::uint32_t>(std::clamp(CPU_COUNT(&affinity), 1, 32));
  EXPECT_EQ(tile_bands(true), usable) << "the CPUs this process may run on";
  setenv("LP_NUM_THREADS", "lots", 1);
  EXPECT_EQ(tile_bands(true), usable) << "a value llvmpipe ignores is ignored";
  if (saved != nullptr) setenv("LP_NUM_THREADS", restore.c_str(), 1);
}

// The per-pixel passes' workgroup shape (shared/pixel_groups.h) by device: rows on a CPU, squares
// on a GPU, set through the two specialisation constants the shaders declare.
TEST(TileOrder, PixelGroupsAreRowsOnCpuDevicesAndSquaresOnGpus) {
  EXPECT_EQ(pixel_group_shape(true), glm::uvec2(gpu::kPixelGroupCpuWidth, 1u));
  EXPECT_EQ(pixel_group_shape(false), glm::uvec2(gpu::kPixelGroupGpuSide));
  using Pairs = std::vector<std::pair<std::uint32_t, std::uint32_t>>;
  const std::span<const runtime::ShaderReflection* const> no_shaders;
  EXPECT_EQ(pixel_group_constants(pixel_group_shape(true)).resolve(no_shaders, "test"),
            (Pairs{{gpu::kPixelGroupWidthId, gpu::kPixelGroupCpuWidth},
                   {gpu::kPixelGroupHeightId, 1u}}));
  EXPECT_EQ(pixel_group_constants(pixel_group_shape(false)).resolve(no_shaders, "test"),
            (Pairs{{gpu::kPixelGroupWidthId, gpu::kPixelGroupGpuSide},
                   {gpu::kPixelGroupHeightId, gpu::kPixelGroupGpuSide}}));
}

}  // namespace
}  // namespace lantern::lighting
