// Headless target: a compute pattern rendered through the render graph into the target's output
// image, read back and checked pixel by pixel, over several frames; then written as EXR with
// write_image and read back with OpenImageIO. Clean under validation (sync validation on).
#include "runtime/target/headless_target.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "runtime/core/device.h"
#include "runtime/gpu/shader_library.h"
#include "runtime/image/image_io.h"
#include "tests/window/pattern_frame.h"

namespace lantern::runtime {
namespace {

constexpr std::uint32_t kWidth = 61;  // not a multiple of the 8x8 workgroup
constexpr std::uint32_t kHeight = 37;

// Number of pixels (channel by channel) that differ from the pattern by more than `tolerance`.
std::size_t pattern_mismatches(const ImageRGBA32F& image, std::uint32_t frame, float tolerance,
                               bool alpha) {
  std::size_t bad = 0;
  for (std::uint32_t y = 0; y < image.height; ++y)
    for (std::uint32_t x = 0; x < image.width; ++x) {
      float want[4];
      test::expected_pattern(x, y, image.width, image.height, frame, want);
      const float* got = image.at(x, y);
      for (int c = 0; c < (alpha ? 4 : 3); ++c)
        if (!(std::fabs(got[c] - want[c]) <= tolerance)) {
          if (bad < 5)
            ADD_FAILURE() << "pixel (" << x << ", " << y << ") channel " << c << ": got " << got[c]
                          << ", want " << want[c];
          ++bad;
        }
    }
  return bad;
}

class HeadlessTargetTest : public ::testing::Test {
 protected:
  void TearDown() override {
    EXPECT_TRUE(device.validation_enabled())
        << "validation layer unavailable: the test cannot vouch for API use";
    EXPECT_EQ(device.validation_errors(), 0u);
  }

  Device device{DeviceOptions{
      .validation = true,
      .sync_validation = true,
      .cache_dir = std::filesystem::temp_directory_path() / "lantern_test_pipeline_cache"}};
  ShaderLibrary shaders;
  ComputePipeline pattern{
      device, shaders.load("tests/window_pattern.comp"), {.name = "test.pattern"}};
  graph::GraphExecutor executor{device};
  graph::RenderGraph graph;
};

TEST_F(HeadlessTargetTest, RendersPatternAndReadsItBackEveryFrame) {
  HeadlessTarget target(device, {.width = kWidth, .height = kHeight});
  EXPECT_EQ(target.render_extent().width, kWidth);
  EXPECT_EQ(target.render_extent().height, kHeight);
  EXPECT_THROW((void)target.read_output(), RuntimeError);  // nothing delivered yet

  for (std::uint32_t frame = 0; frame < 3; ++frame) {
    ASSERT_TRUE(test::render_pattern_frame(target, graph, executor, pattern, frame));
    const ImageRGBA32F image = target.read_output();
    ASSERT_EQ(image.width, kWidth);
    ASSERT_EQ(image.height, kHeight);
    // x / width in float on the GPU and the CPU: allow one ULP of [0,1) for the division.
    EXPECT_EQ(pattern_mismatches(image, frame, 1e-7f, true), 0u) << "frame " << frame;
  }
  EXPECT_EQ(target.frames_delivered(), 3u);
}

TEST_F(HeadlessTargetTest, OutputWritesAndReadsBackAsExr) {
  HeadlessTarget target(device, {.width = kWidth, .height = kHeight});
  ASSERT_TRUE(test::render_pattern_frame(target, graph, executor, pattern, 5));
  const ImageRGBA32F image = target.read_output();

  const auto path = std::filesystem::temp_directory_path() /
                    ("lantern_headless_target_" + std::to_string(::getpid()) + ".exr");
  write_image(path, image);
  const ImageRGBA32F file = read_image(path);
  std::filesystem::remove(path);
  ASSERT_EQ(file.width, kWidth);
  ASSERT_EQ(file.height, kHeight);
  // EXR is float RGB: the round trip is exact; alpha is not stored (reads as 1).
  for (std::uint32_t y = 0; y < kHeight; ++y)
    for (std::uint32_t x = 0; x < kWidth; ++x)
      for (int c = 0; c < 3; ++c)
        ASSERT_EQ(file.at(x, y)[c], image.at(x, y)[c]) << "(" << x << ", " << y << ") c" << c;
  EXPECT_EQ(pattern_mismatches(file, 5, 1e-7f, false), 0u);
}

TEST_F(HeadlessTargetTest, RejectsZeroSize) {
  EXPECT_THROW(HeadlessTarget(device, {.width = 0, .height = 10}), InputError);
}

}  // namespace
}  // namespace lantern::runtime
