// Image I/O: EXR keeps linear float radiance exactly; PNG applies the shared tonemap + sRGB;
// failed writes leave nothing behind; NaN/Inf images are refused.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>

#include "engine/core/error.h"
#include "runtime/image/image_io.h"
#include "shared/tonemap.h"

namespace fs = std::filesystem;
using lantern::runtime::ImageRGBA32F;

namespace {

fs::path temp_dir() {
  fs::path dir = fs::temp_directory_path() / ("lantern_image_io_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir;
}

ImageRGBA32F gradient(std::uint32_t w, std::uint32_t h) {
  ImageRGBA32F img(w, h);
  for (std::uint32_t y = 0; y < h; ++y)
    for (std::uint32_t x = 0; x < w; ++x) {
      float* p = img.at(x, y);
      p[0] = 0.001f * x;            // dim
      p[1] = 1000.0f * (y + 1);     // very bright
      p[2] = 1e-7f * (x + y + 1);   // tiny
      p[3] = 1.0f;
    }
  return img;
}

}  // namespace

TEST(ImageIo, ExrRoundTripIsExactLinearFloat) {
  const fs::path path = temp_dir() / "gradient.exr";
  const ImageRGBA32F img = gradient(7, 5);
  lantern::runtime::write_image(path, img);
  const ImageRGBA32F back = lantern::runtime::read_image(path);
  ASSERT_EQ(back.width, 7u);
  ASSERT_EQ(back.height, 5u);
  for (std::uint32_t y = 0; y < 5; ++y)
    for (std::uint32_t x = 0; x < 7; ++x)
      for (int c = 0; c < 3; ++c) EXPECT_EQ(back.at(x, y)[c], img.at(x, y)[c]) << x << "," << y;
  fs::remove_all(path.parent_path());
}

TEST(ImageIo, PngIsTonemappedSrgbTopLeftFirst) {
  const fs::path path = temp_dir() / "tonemapped.png";
  ImageRGBA32F img(2, 2);
  img.at(0, 0)[0] = 0.18f;  // mid grey in the red channel of the top-left pixel
  img.at(1, 1)[1] = 1e6f;   // saturates
  lantern::runtime::write_image(path, img, 1.0f);
  const ImageRGBA32F back = lantern::runtime::read_image(path);
  const float expected = lantern::gpu::srgb_encode(lantern::gpu::tonemap_filmic(0.18f));
  EXPECT_NEAR(back.at(0, 0)[0], expected, 0.5f / 255.0f);
  EXPECT_EQ(back.at(0, 0)[1], 0.0f);
  EXPECT_NEAR(back.at(1, 1)[1], 1.0f, 1e-6f);
  EXPECT_EQ(back.at(1, 0)[0], 0.0f);
  fs::remove_all(path.parent_path());
}

TEST(ImageIo, RefusesNonFiniteAndLeavesNothingBehind) {
  const fs::path dir = temp_dir();
  ImageRGBA32F img = gradient(4, 4);
  img.at(2, 3)[1] = std::numeric_limits<float>::quiet_NaN();
  img.at(0, 0)[0] = std::numeric_limits<float>::infinity();
  try {
    lantern::runtime::write_image(dir / "bad.exr", img);
    FAIL() << "a NaN image was written";
  } catch (const lantern::RuntimeError& e) {
    EXPECT_NE(std::string(e.what()).find("2 NaN/Inf pixels"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(fs::is_empty(dir));
  fs::remove_all(dir);
}

TEST(ImageIo, BadPathsAreInputErrors) {
  const ImageRGBA32F img = gradient(2, 2);
  EXPECT_THROW(lantern::runtime::write_image("/nonexistent_dir_xyz/out.exr", img), lantern::InputError);
  EXPECT_THROW(lantern::runtime::write_image(temp_dir() / "out.bmp", img), lantern::InputError);
  EXPECT_THROW(lantern::runtime::read_image("/nonexistent_dir_xyz/in.exr"), lantern::InputError);
  fs::remove_all(temp_dir());
}

TEST(Tonemap, MonotonicAndBounded) {
  float previous = -1.0f;
  for (float x = 0.0f; x < 100.0f; x = x * 1.5f + 0.001f) {
    const float y = lantern::gpu::tonemap_filmic(x);
    EXPECT_GE(y, previous);
    EXPECT_LE(y, 1.0f);
    previous = y;
  }
  EXPECT_EQ(lantern::gpu::tonemap_to_srgb(lantern::gpu::vec3(NAN, INFINITY, -1.0f), 1.0f),
            lantern::gpu::vec3(0.0f));
}
