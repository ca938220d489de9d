// auto_exposure (lighting/integrators/auto_exposure.h) against its closed form:
// 0.18 / exp(mean over lit pixels of log(1e-4 + Y)), Y = 0.2126 r + 0.7152 g + 0.0722 b, with
// black and non-finite pixels left out, and 1 when no pixel is lit.
#include "lighting/integrators/auto_exposure.h"

#include <gtest/gtest.h>

#include <cmath>
#include <glm/glm.hpp>
#include <limits>
#include <vector>

namespace lantern::lighting {
namespace {

runtime::ImageRGBA32F image_of(const std::vector<glm::vec3>& rgb) {
  runtime::ImageRGBA32F image(static_cast<std::uint32_t>(rgb.size()), 1);
  for (std::size_t i = 0; i < rgb.size(); ++i) {
    image.pixels[4 * i] = rgb[i].r;
    image.pixels[4 * i + 1] = rgb[i].g;
    image.pixels[4 * i + 2] = rgb[i].b;
    image.pixels[4 * i + 3] = 1.0f;
  }
  return image;
}

TEST(AutoExposure, UniformGreyMapsToMiddleGrey) {
  for (const float y : {1e-3f, 0.18f, 1.0f, 250.0f}) {
    const float e = auto_exposure(image_of(std::vector<glm::vec3>(16, glm::vec3(y))));
    EXPECT_NEAR(e, 0.18 / (1e-4 + y), 1e-5 * e) << "grey " << y;
  }
}

// The Rec.709 weights: pure red, green and blue pixels of one image, Y = 0.2126 x 4, 0.7152 x 2,
// 0.0722 x 10: the log average of the three.
TEST(AutoExposure, LogAverageOfRec709Luminance) {
  const std::vector<glm::vec3> rgb = {glm::vec3(4.0f, 0.0f, 0.0f), glm::vec3(0.0f, 2.0f, 0.0f),
                                      glm::vec3(0.0f, 0.0f, 10.0f)};
  const double log_mean =
      (std::log(1e-4 + 0.2126 * 4.0) + std::log(1e-4 + 0.7152 * 2.0) + std::log(1e-4 + 0.722)) /
      3.0;
  const float e = auto_exposure(image_of(rgb));
  EXPECT_NEAR(e, 0.18 / std::exp(log_mean), 1e-5 * e);
}

// A geometric, not arithmetic, mean: half the pixels at 100, half at 0.01 give the key of
// sqrt(100 * 0.01) = 1 (plus the 1e-4 floor), where the arithmetic mean would be ~50.
TEST(AutoExposure, DecadesAverageGeometrically) {
  std::vector<glm::vec3> rgb(8, glm::vec3(100.0f));
  rgb.resize(16, glm::vec3(0.01f));
  const float e = auto_exposure(image_of(rgb));
  EXPECT_NEAR(e, 0.18 / std::sqrt((100.0 + 1e-4) * (0.01 + 1e-4)), 1e-5 * e);
}

// Scaling the image by k scales the exposure by 1/k where the floor is negligible.
TEST(AutoExposure, ScalesInverselyWithRadiance) {
  std::vector<glm::vec3> rgb;
  for (int i = 0; i < 64; ++i) rgb.emplace_back(0.5f + 0.1f * float(i % 7), 1.0f, 2.0f);
  const float base = auto_exposure(image_of(rgb));
  for (glm::vec3& c : rgb) c *= 1000.0f;
  EXPECT_NEAR(auto_exposure(image_of(rgb)) * 1000.0f, base, 1e-3 * base);
}

// Black (background, full shadow), negative-luminance and NaN/Inf pixels are left out: adding
// them changes nothing.
TEST(AutoExposure, BlackAndNonFinitePixelsAreLeftOut) {
  const std::vector<glm::vec3> lit = {glm::vec3(0.3f), glm::vec3(3.0f), glm::vec3(0.03f)};
  const float expected = auto_exposure(image_of(lit));
  std::vector<glm::vec3> mixed = lit;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  for (const glm::vec3& bad : {glm::vec3(0.0f), glm::vec3(0.0f), glm::vec3(nan, 1.0f, 1.0f),
                               glm::vec3(inf), glm::vec3(-1.0f), glm::vec3(1.0f, -inf, 1.0f)}) {
    mixed.push_back(bad);
  }
  EXPECT_FLOAT_EQ(auto_exposure(image_of(mixed)), expected);
}

TEST(AutoExposure, NoLitPixelGivesOne) {
  EXPECT_EQ(auto_exposure(runtime::ImageRGBA32F()), 1.0f);
  EXPECT_EQ(auto_exposure(image_of(std::vector<glm::vec3>(9, glm::vec3(0.0f)))), 1.0f);
  EXPECT_EQ(auto_exposure(image_of({glm::vec3(std::numeric_limits<float>::quiet_NaN())})), 1.0f);
}

}  // namespace
}  // namespace lantern::lighting
