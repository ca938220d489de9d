// runtime::Swapchain: the VkSwapchainKHR of one surface, its images and views, recreated for a
// new size or after VK_ERROR_OUT_OF_DATE_KHR / VK_SUBOPTIMAL_KHR. Images are written by a
// compute pass (storage usage; the pass encodes sRGB since storage on *_SRGB formats is rare),
// and are meant to be imported into the render graph with import_info().
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>
#include <vector>

#include "runtime/graph/graph_decl.h"
#include "runtime/window/present_mode.h"

namespace lantern::runtime {

class Device;

struct SwapchainDesc {
  PresentMode present_mode = PresentMode::Fifo;  // falls back to Fifo (logged) when unsupported
  std::uint32_t min_images = 3;                  // clamped to what the surface allows
  VkImageUsageFlags usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
};

// What acquire() and present() report. Suboptimal still acquired/presented the image.
enum class SwapchainStatus { Ok, Suboptimal, OutOfDate };

struct SwapchainImage {
  VkImage image = VK_NULL_HANDLE;
  VkImageView view = VK_NULL_HANDLE;
  VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;  // last known (PRESENT_SRC once presented)
};

class Swapchain {
 public:
  // Throws lantern::RuntimeError when the surface offers no format usable as a storage image.
  Swapchain(Device& device, VkSurfaceKHR surface, VkExtent2D framebuffer,
            const SwapchainDesc& desc = {});
  ~Swapchain();
  Swapchain(const Swapchain&) = delete;
  Swapchain& operator=(const Swapchain&) = delete;

  // Waits for the device, then replaces the swapchain (the old one is passed as oldSwapchain).
  // `framebuffer` must be non-zero: a minimised window keeps its swapchain and skips frames.
  void recreate(VkExtent2D framebuffer);

  // Acquires the next image, signalling `signal` when it may be written. OutOfDate: nothing was
  // acquired and `signal` is untouched; recreate and try again.
  SwapchainStatus acquire(VkSemaphore signal, std::uint32_t* index);
  // Presents image `index` after `wait`; records the image as PRESENT_SRC.
  SwapchainStatus present(std::uint32_t index, VkSemaphore wait);

  // Render-graph import of image `index` for this frame: contents discarded (UNDEFINED), first
  // use after `acquire_wait_stage` (the stage the acquire semaphore is waited at), left in
  // PRESENT_SRC.
  graph::ImportInfo import_info(VkPipelineStageFlags2 acquire_wait_stage) const;

  VkSwapchainKHR handle() const { return swapchain_; }
  VkFormat format() const { return format_; }
  VkColorSpaceKHR color_space() const { return color_space_; }
  VkExtent2D extent() const { return extent_; }
  PresentMode present_mode() const { return present_mode_; }
  std::uint32_t image_count() const { return static_cast<std::uint32_t>(images_.size()); }
  const SwapchainImage& image(std::uint32_t index) const { return images_.at(index); }
  // One per image (signalled by the frame's submit, waited by present); stable across recreate.
  VkSemaphore render_finished(std::uint32_t index) const { return render_finished_.at(index); }
  // 1 after construction, +1 per recreate().
  std::uint64_t generation() const { return generation_; }

 private:
  void create(VkExtent2D framebuffer, VkSwapchainKHR old);
  void destroy_views();

  Device& device_;
  VkSurfaceKHR surface_;
  SwapchainDesc desc_;
  VkSwapchainKHR swapchain_ = VK_NULL_HANDLE;
  VkFormat format_ = VK_FORMAT_UNDEFINED;
  VkColorSpaceKHR color_space_ = VK_COLOR_SPACE_SRGB_NONLINEAR_KHR;
  VkExtent2D extent_{};
  PresentMode present_mode_ = PresentMode::Fifo;
  std::vector<SwapchainImage> images_;
  std::vector<VkSemaphore> render_finished_;
  std::uint64_t generation_ = 0;
};

}  // namespace lantern::runtime
