// Window frames: acquire (recreating when stale), present pass, submit and present.
#include "runtime/target/window_target.h"

#include <fmt/format.h>

#include "engine/core/error.h"
#include "engine/core/log.h"
#include "runtime/core/device.h"
#include "runtime/window/window.h"

namespace lantern::runtime {
namespace {

VkExtent2D to_extent(FramebufferSize size) {
  return {size.width, size.height};
}

bool same(VkExtent2D a, VkExtent2D b) {
  return a.width == b.width && a.height == b.height;
}

}  // namespace

WindowTarget::WindowTarget(Device& device, Window& window, const WindowTargetDesc& desc)
    : device_(device),
      window_(window),
      desc_(desc),
      surface_(device, window),
      slots_(device, desc.frames_in_flight),
      present_(device, shaders_) {
  if (desc.frames_in_flight == 0) throw InputError("window target: frames_in_flight must be >= 1");
  if ((desc.render_width == 0) != (desc.render_height == 0))
    throw InputError(fmt::format("window target: render size {}x{} must be both zero or both set",
                                 desc.render_width, desc.render_height));
  framebuffer_ = to_extent(window.framebuffer_size());
  if (framebuffer_.width == 0 || framebuffer_.height == 0)
    throw RuntimeError("window target: the window is minimised (0 x 0) at creation");
  swapchain_ = std::make_unique<Swapchain>(device, surface_.handle(), framebuffer_, desc.swapchain);
  const VkExtent2D render = desc.render_width != 0
                                ? VkExtent2D{desc.render_width, desc.render_height}
                                : swapchain_->extent();
  output_ = std::make_unique<OutputImage>(device, render, "target.output");
  present_.warm_up();
}

WindowTarget::~WindowTarget() {
  slots_.wait_all();
}

void WindowTarget::recreate(VkExtent2D framebuffer) {
  slots_.wait_all();
  swapchain_->recreate(framebuffer);
  framebuffer_ = framebuffer;
  stale_ = false;
  if (desc_.render_width == 0 && !same(output_->extent(), swapchain_->extent()))
    output_->resize(swapchain_->extent());
}

std::optional<TargetFrame> WindowTarget::begin_frame() {
  const VkExtent2D framebuffer = to_extent(window_.framebuffer_size());
  if (window_.minimized()) {
    ++skipped_;
    return std::nullopt;
  }
  if (stale_ || !same(framebuffer, framebuffer_)) recreate(framebuffer);

  const std::uint32_t slot = static_cast<std::uint32_t>(frame_index_ % slots_.count());
  slots_.wait(slot);  // the slot's acquire semaphore and command buffer are free again
  SwapchainStatus status = swapchain_->acquire(slots_.acquire_semaphore(slot), &image_index_);
  if (status == SwapchainStatus::OutOfDate) {
    recreate(framebuffer);
    status = swapchain_->acquire(slots_.acquire_semaphore(slot), &image_index_);
    if (status == SwapchainStatus::OutOfDate) {
      ++skipped_;
      return std::nullopt;  // the window is changing under us; try again next iteration
    }
  }
  if (status == SwapchainStatus::Suboptimal) stale_ = true;  // use it, recreate after present
  return TargetFrame{slots_.begin(slot), slot, frame_index_++, output_->extent()};
}

graph::ImageHandle WindowTarget::import_output(graph::RenderGraph& graph, const TargetFrame&) {
  return output_->import(graph, PresentPass::source_state());
}

void WindowTarget::add_delivery(graph::RenderGraph& graph, const TargetFrame&,
                                graph::ImageHandle output) {
  const SwapchainImage& image = swapchain_->image(image_index_);
  graph::ImageDesc desc;
  desc.extent = {swapchain_->extent().width, swapchain_->extent().height, 1};
  desc.format = swapchain_->format();
  const graph::ImageHandle destination =
      graph.import_image("swapchain", image.image, image.view, desc,
                         swapchain_->import_info(PresentPass::kDestinationStage));
  present_.add(graph, output, output_->extent(), destination, swapchain_->extent());
}

void WindowTarget::end_frame(const TargetFrame& frame) {
  const VkSemaphore rendered = swapchain_->render_finished(image_index_);
  slots_.submit(frame.slot, slots_.acquire_semaphore(frame.slot),
                VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, rendered);
  output_->commit();
  const SwapchainStatus status = swapchain_->present(image_index_, rendered);
  if (status != SwapchainStatus::Ok) stale_ = true;
}

}  // namespace lantern::runtime
