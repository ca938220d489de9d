#include "runtime/image/image_metrics.h"

#include <gtest/gtest.h>

#include "engine/core/error.h"

namespace lantern::runtime {
namespace {

ImageRGBA32F constant(std::uint32_t w, std::uint32_t h, float v) {
  ImageRGBA32F img(w, h);
  for (std::size_t i = 0; i < img.pixels.size(); ++i) img.pixels[i] = (i % 4 == 3) ? 1.0f : v;
  return img;
}

TEST(ImageMetrics, RelativeMseOfKnownErrors) {
  const ImageRGBA32F ref = constant(4, 2, 1.0f);
  EXPECT_DOUBLE_EQ(relative_mse(ref, ref), 0.0);
  const ImageRGBA32F off = constant(4, 2, 1.5f);  // (0.5^2) / (1 + 0.01)
  EXPECT_NEAR(relative_mse(off, ref), 0.25 / 1.01, 1e-12);
  EXPECT_NEAR(relative_mse(off, ref, 0.0), 0.25, 1e-12);
}

TEST(ImageMetrics, MaskSelectsPixels) {
  const ImageRGBA32F ref = constant(2, 1, 2.0f);
  ImageRGBA32F img = ref;
  img.at(1, 0)[0] = 4.0f;  // only pixel 1, red channel: (2^2)/(4)/3
  EXPECT_NEAR(relative_mse(img, ref, {0, 1}, 0.0), 1.0 / 3.0, 1e-12);
  EXPECT_DOUBLE_EQ(relative_mse(img, ref, {1, 0}, 0.0), 0.0);
  EXPECT_DOUBLE_EQ(relative_mse(img, ref, {0, 0}, 0.0), 0.0);
  EXPECT_THROW(relative_mse(img, ref, {1}, 0.0), InputError);
}

TEST(ImageMetrics, SizeMismatchIsAnError) {
  EXPECT_THROW(relative_mse(constant(2, 2, 1.0f), constant(2, 3, 1.0f)), InputError);
}

TEST(ImageMetrics, AccumulatorMeansFramesInDouble) {
  ImageAccumulator acc;
  acc.add(constant(3, 3, 1.0f));
  acc.add(constant(3, 3, 2.0f));
  acc.add(constant(3, 3, 6.0f));
  EXPECT_EQ(acc.count(), 3u);
  EXPECT_FLOAT_EQ(acc.mean().at(2, 2)[1], 3.0f);
  EXPECT_DOUBLE_EQ(mean_rgb(acc.mean()), 3.0);
  EXPECT_THROW(acc.add(constant(2, 3, 1.0f)), InputError);
}

}  // namespace
}  // namespace lantern::runtime
