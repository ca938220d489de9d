// WindowTarget: frames for a Window through a Swapchain. The output image follows the
// framebuffer size (or stays fixed); target.present copies it to the acquired swapchain image.
// Resize, VK_ERROR_OUT_OF_DATE_KHR and VK_SUBOPTIMAL_KHR recreate the swapchain; a minimised
// window (0 x 0) yields no frames and keeps its swapchain.
#pragma once

#include <memory>

#include "runtime/gpu/shader_library.h"
#include "runtime/target/frame_slots.h"
#include "runtime/target/output_image.h"
#include "runtime/target/present_pass.h"
#include "runtime/target/render_target.h"
#include "runtime/window/surface.h"
#include "runtime/window/swapchain.h"

namespace lantern::runtime {

class Device;
class Window;

struct WindowTargetDesc {
  SwapchainDesc swapchain;
  std::uint32_t frames_in_flight = 2;  // CPU may record frame N+1 while the GPU runs frame N
  // Render size; 0 x 0 = the framebuffer size, following resizes. Otherwise fixed and scaled to
  // the window by target.present.
  std::uint32_t render_width = 0;
  std::uint32_t render_height = 0;
};

class WindowTarget final : public RenderTarget {
 public:
  // The Device must have been created with enable_presentation(); the window must outlive this.
  WindowTarget(Device& device, Window& window, const WindowTargetDesc& desc = {});
  ~WindowTarget() override;

  std::optional<TargetFrame> begin_frame() override;
  graph::ImageHandle import_output(graph::RenderGraph& graph, const TargetFrame& frame) override;
  void add_delivery(graph::RenderGraph& graph, const TargetFrame& frame,
                    graph::ImageHandle output) override;
  void end_frame(const TargetFrame& frame) override;
  VkExtent2D render_extent() const override { return output_->extent(); }
  std::uint32_t frames_in_flight() const override { return slots_.count(); }

  const Swapchain& swapchain() const { return *swapchain_; }
  // Swapchain image acquired for the current frame (valid between begin_frame and end_frame).
  std::uint32_t image_index() const { return image_index_; }
  // Frames skipped because the window was minimised or the swapchain could not be acquired.
  std::uint64_t skipped_frames() const { return skipped_; }

 private:
  void recreate(VkExtent2D framebuffer);

  Device& device_;
  Window& window_;
  WindowTargetDesc desc_;
  ShaderLibrary shaders_;
  Surface surface_;
  std::unique_ptr<Swapchain> swapchain_;
  FrameSlots slots_;
  std::unique_ptr<OutputImage> output_;
  PresentPass present_;
  VkExtent2D framebuffer_{};  // the framebuffer size the swapchain was made for
  bool stale_ = false;        // suboptimal or out of date at present: recreate before next frame
  std::uint32_t image_index_ = 0;
  std::uint64_t frame_index_ = 0;
  std::uint64_t skipped_ = 0;
};

}  // namespace lantern::runtime
