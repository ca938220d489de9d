#include "runtime/image/image_metrics.h"

#include <gtest/gtest.h>

#include <cmath>

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

// Frames 1, 2, 6: mean 3, sample variance ((-2)^2 + (-1)^2 + 3^2) / 2 = 7, so the mean's
// standard error is sqrt(7 / 3); its relative noise against the mean is (7 / 3) / (9 + epsilon).
TEST(ImageMetrics, AccumulatorStandardErrorOfTheMean) {
  ImageAccumulator acc;
  acc.add(constant(2, 2, 1.0f));
  EXPECT_THROW((void)acc.standard_error(), InputError) << "one frame has no spread";
  acc.add(constant(2, 2, 2.0f));
  acc.add(constant(2, 2, 6.0f));
  const ImageRGBA32F se = acc.standard_error();
  EXPECT_NEAR(se.at(1, 1)[0], std::sqrt(7.0 / 3.0), 1e-6);
  EXPECT_EQ(se.at(1, 1)[3], 1.0f);
  EXPECT_NEAR(relative_mse_of_noise(acc.mean(), se), (7.0 / 3.0) / (9.0 + 0.01), 1e-6);
  EXPECT_NEAR(relative_mse_of_noise(acc.mean(), se, 0.0), 7.0 / 27.0, 1e-6);
  // Equal frames: no noise.
  ImageAccumulator still;
  still.add(constant(2, 2, 5.0f));
  still.add(constant(2, 2, 5.0f));
  EXPECT_EQ(relative_mse_of_noise(still.mean(), still.standard_error()), 0.0);
  EXPECT_THROW(relative_mse_of_noise(constant(2, 2, 1.0f), constant(3, 2, 1.0f)), InputError);
}

}  // namespace
}  // namespace lantern::runtime
