// Window target under X (Xvfb in CI): present frames of a compute pattern, resize the window,
// present more, and check the swapchain followed the framebuffer, the render size followed the
// swapchain and validation stayed silent. Without DISPLAY this FAILS: the suite runs under
// xvfb-run (scripts/test.sh), and a window test that silently skips proves nothing.
#include <GLFW/glfw3.h>
#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <memory>

#include "engine/core/log.h"
#include "runtime/core/device.h"
#include "runtime/gpu/shader_library.h"
#include "runtime/target/window_target.h"
#include "runtime/window/presentation.h"
#include "runtime/window/window.h"
#include "tests/window/pattern_frame.h"

namespace lantern::runtime {
namespace {

constexpr int kFramesPerPhase = 30;

bool have_display() {
  const char* display = std::getenv("DISPLAY");
  return display != nullptr && *display != '\0';
}

// Device options for presenting, validated; GLFW is initialised by enable_presentation.
struct PresentingDevice {
  PresentingDevice() {
    options.validation = true;
    options.cache_dir = std::filesystem::temp_directory_path() / "lantern_test_pipeline_cache";
    glfw = enable_presentation(options);
    device = std::make_unique<Device>(options);
  }
  DeviceOptions options;
  std::shared_ptr<GlfwLibrary> glfw;
  std::unique_ptr<Device> device;
};

class WindowTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(have_display())
        << "DISPLAY is not set: the window test needs an X server. Run it under `xvfb-run -a` "
           "(scripts/test.sh does)";
    gpu = std::make_unique<PresentingDevice>();
    pattern =
        std::make_unique<ComputePipeline>(*gpu->device, shaders.load("tests/window_pattern.comp"),
                                          ComputePipelineDesc{.name = "test.pattern"});
    executor = std::make_unique<graph::GraphExecutor>(*gpu->device);
  }
  void TearDown() override {
    if (!gpu) return;
    EXPECT_TRUE(gpu->device->validation_enabled())
        << "validation layer unavailable: the test cannot vouch for API use";
    EXPECT_EQ(gpu->device->validation_errors(), 0u);
  }

  // Presents `count` frames; returns how many were skipped (window gave no frame).
  int present(WindowTarget& target, Window& window, int count) {
    int skipped = 0;
    for (int i = 0; i < count; ++i) {
      window.poll_events();
      if (!test::render_pattern_frame(target, graph, *executor, *pattern,
                                      static_cast<std::uint32_t>(frame_++)))
        ++skipped;
    }
    return skipped;
  }

  std::unique_ptr<PresentingDevice> gpu;
  ShaderLibrary shaders;
  std::unique_ptr<ComputePipeline> pattern;
  std::unique_ptr<graph::GraphExecutor> executor;
  graph::RenderGraph graph;
  int frame_ = 0;
};

TEST_F(WindowTest, PresentsResizesAndRecreatesSwapchain) {
  Window window({.title = "lantern window test", .width = 320, .height = 180});
  const FramebufferSize first = window.framebuffer_size();
  ASSERT_FALSE(window.minimized());
  std::uint64_t callback_resizes = 0;
  window.on_framebuffer_resize([&](FramebufferSize) { ++callback_resizes; });

  WindowTarget target(*gpu->device, window);
  EXPECT_EQ(target.frames_in_flight(), 2u);
  EXPECT_EQ(target.swapchain().present_mode(), PresentMode::Fifo);
  EXPECT_EQ(target.swapchain().generation(), 1u);
  EXPECT_EQ(target.swapchain().extent().width, first.width);
  EXPECT_EQ(target.swapchain().extent().height, first.height);

  const auto start = std::chrono::steady_clock::now();
  EXPECT_EQ(present(target, window, kFramesPerPhase), 0);
  gpu->device->wait_idle();
  const double ms_per_frame =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count() /
      kFramesPerPhase;
  log::info("window test: {:.2f} ms per frame at {}x{} (pattern + present, fifo)", ms_per_frame,
            first.width, first.height);
  EXPECT_EQ(target.swapchain().generation(), 1u) << "no resize yet: no recreation expected";

  // Resize, then process events until the framebuffer follows (the X server answers async).
  window.set_size(400, 240);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  while (window.framebuffer_size() == first && std::chrono::steady_clock::now() < deadline)
    window.wait_events(0.01);
  const FramebufferSize second = window.framebuffer_size();
  ASSERT_NE(second, first) << "the framebuffer did not change size within 5 s of set_size";
  EXPECT_GE(window.resize_count(), 1u);
  EXPECT_EQ(callback_resizes, window.resize_count());

  EXPECT_EQ(present(target, window, kFramesPerPhase), 0);
  EXPECT_GE(target.swapchain().generation(), 2u) << "the swapchain was not recreated on resize";
  EXPECT_EQ(target.swapchain().extent().width, second.width);
  EXPECT_EQ(target.swapchain().extent().height, second.height);
  EXPECT_EQ(target.render_extent().width, second.width) << "render size follows the framebuffer";
  EXPECT_EQ(target.render_extent().height, second.height);
  EXPECT_EQ(target.skipped_frames(), 0u);
  for (std::uint32_t i = 0; i < target.swapchain().image_count(); ++i) {
    EXPECT_NE(target.swapchain().image(i).view, VkImageView{VK_NULL_HANDLE});
    EXPECT_EQ(target.swapchain().image(i).layout, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR)
        << "image " << i << " was never presented after the resize";
  }

  window.capture_cursor(true);
  EXPECT_TRUE(window.cursor_captured());
  window.poll_events();
  window.capture_cursor(false);
  EXPECT_FALSE(window.input().key_down(GLFW_KEY_W)) << "no key was pressed";

  EXPECT_FALSE(window.should_close());
  window.request_close();
  EXPECT_TRUE(window.should_close());
}

TEST_F(WindowTest, EveryPresentModeWorksWithAFixedRenderSize) {
  Window window({.title = "lantern present modes", .width = 200, .height = 120});
  for (PresentMode mode : {PresentMode::Fifo, PresentMode::Mailbox, PresentMode::Immediate}) {
    WindowTargetDesc desc;
    desc.swapchain.present_mode = mode;
    desc.render_width = 96;  // scaled to the window by target.present
    desc.render_height = 64;
    WindowTarget target(*gpu->device, window, desc);
    EXPECT_EQ(target.swapchain().present_mode(), mode)
        << present_mode_name(mode) << " fell back (PLATFORM.md: Xvfb supports all modes)";
    EXPECT_EQ(present(target, window, 5), 0) << present_mode_name(mode);
    EXPECT_EQ(target.render_extent().width, 96u);
    EXPECT_EQ(target.render_extent().height, 64u);
  }
}

TEST(WindowInput, PresentModeNames) {
  EXPECT_EQ(parse_present_mode("mailbox"), PresentMode::Mailbox);
  EXPECT_EQ(parse_present_mode("immediate"), PresentMode::Immediate);
  EXPECT_EQ(parse_present_mode("fifo"), PresentMode::Fifo);
  EXPECT_THROW(parse_present_mode("vsync"), InputError);
}

}  // namespace
}  // namespace lantern::runtime
