// The à-trous passes' pixel pairs (shared/denoise.h): the threads of a row, pair by pair, cover
// every pixel exactly once at every tap spacing, for widths that are and are not multiples of
// the pairs' blocks.
#include <gtest/gtest.h>

#include <vector>

#include "shared/denoise.h"

namespace lantern {
namespace {

TEST(DenoisePairsTest, ThreadsCoverEveryPixelOfARowOnce) {
  for (std::uint32_t step = 1; step <= (1u << (gpu::kDenoiseMaxAtrousIterations - 1)); step *= 2) {
    for (std::uint32_t width = 1; width <= 130; ++width) {
      std::vector<int> hits(width, 0);
      const std::uint32_t columns = gpu::denoise_atrous_pair_columns(width, step);
      for (std::uint32_t c = 0; c < columns; ++c) {
        const std::uint32_t x0 = gpu::denoise_atrous_pair_first(c, step);
        if (x0 < width) ++hits[x0];
        if (x0 < width && x0 + step < width) ++hits[x0 + step];
      }
      for (std::uint32_t x = 0; x < width; ++x) {
        ASSERT_EQ(hits[x], 1) << "pixel " << x << " of a " << width << "-pixel row, step " << step;
      }
      // No more threads than pixels need: at most one block's worth beyond half the row.
      EXPECT_LE(columns, width / 2 + step) << "width " << width << ", step " << step;
    }
  }
}

}  // namespace
}  // namespace lantern
