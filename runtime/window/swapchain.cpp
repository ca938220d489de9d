// Swapchain creation: format, present mode, extent and image count chosen from what the surface
// supports; per-image views and render-finished semaphores.
#include "runtime/window/swapchain.h"

#include <fmt/format.h>

#include <algorithm>

#include "engine/core/error.h"
#include "engine/core/log.h"
#include "runtime/core/device.h"
#include "runtime/core/vk_check.h"

namespace lantern::runtime {
namespace {

template <class T, class Fn>
std::vector<T> enumerate(Fn&& fn) {
  std::uint32_t count = 0;
  VK_CHECK(fn(&count, static_cast<T*>(nullptr)));
  std::vector<T> items(count);
  VK_CHECK(fn(&count, items.data()));
  items.resize(count);
  return items;
}

// A UNORM 8-bit format in the sRGB colour space that can be a storage image: the present pass
// writes it and applies the sRGB encoding itself.
VkSurfaceFormatKHR choose_format(const Device& device, VkSurfaceKHR surface) {
  const auto formats = enumerate<VkSurfaceFormatKHR>([&](std::uint32_t* n, VkSurfaceFormatKHR* p) {
    return vkGetPhysicalDeviceSurfaceFormatsKHR(device.physical_device(), surface, n, p);
  });
  for (VkFormat wanted : {VK_FORMAT_B8G8R8A8_UNORM, VK_FORMAT_R8G8B8A8_UNORM}) {
    VkFormatProperties props{};
    vkGetPhysicalDeviceFormatProperties(device.physical_device(), wanted, &props);
    if ((props.optimalTilingFeatures & VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT) == 0) continue;
    for (const auto& f : formats)
      if (f.format == wanted && f.colorSpace == VK_COLOR_SPACE_SRGB_NONLINEAR_KHR) return f;
  }
  std::string offered;
  for (const auto& f : formats)
    offered += fmt::format("{}{}", offered.empty() ? "" : ", ", static_cast<int>(f.format));
  throw RuntimeError(fmt::format(
      "swapchain: the surface offers no B8G8R8A8_UNORM or R8G8B8A8_UNORM (sRGB colour space) "
      "format usable as a storage image on '{}'; offered VkFormats: {}",
      device.info().name, offered));
}

PresentMode choose_present_mode(const Device& device, VkSurfaceKHR surface, PresentMode wanted) {
  const auto modes = enumerate<VkPresentModeKHR>([&](std::uint32_t* n, VkPresentModeKHR* p) {
    return vkGetPhysicalDeviceSurfacePresentModesKHR(device.physical_device(), surface, n, p);
  });
  if (std::find(modes.begin(), modes.end(), to_vk(wanted)) != modes.end()) return wanted;
  log::warn("present mode {} is not supported by this surface: using fifo",
            present_mode_name(wanted));
  return PresentMode::Fifo;  // the only mode every surface must support
}

}  // namespace

Swapchain::Swapchain(Device& device, VkSurfaceKHR surface, VkExtent2D framebuffer,
                     const SwapchainDesc& desc)
    : device_(device), surface_(surface), desc_(desc) {
  const VkSurfaceFormatKHR format = choose_format(device_, surface_);
  format_ = format.format;
  color_space_ = format.colorSpace;
  present_mode_ = choose_present_mode(device_, surface_, desc_.present_mode);
  create(framebuffer, VK_NULL_HANDLE);
}

Swapchain::~Swapchain() {
  vkDeviceWaitIdle(device_.handle());
  destroy_views();
  for (VkSemaphore s : render_finished_) vkDestroySemaphore(device_.handle(), s, nullptr);
  if (swapchain_ != VK_NULL_HANDLE) vkDestroySwapchainKHR(device_.handle(), swapchain_, nullptr);
}

void Swapchain::recreate(VkExtent2D framebuffer) {
  device_.wait_idle();
  destroy_views();
  VkSwapchainKHR old = swapchain_;
  swapchain_ = VK_NULL_HANDLE;
  try {
    create(framebuffer, old);
  } catch (...) {
    vkDestroySwapchainKHR(device_.handle(), old, nullptr);
    throw;
  }
  vkDestroySwapchainKHR(device_.handle(), old, nullptr);
}

void Swapchain::create(VkExtent2D framebuffer, VkSwapchainKHR old) {
  if (framebuffer.width == 0 || framebuffer.height == 0)
    throw RuntimeError("swapchain: cannot create for a 0 x 0 framebuffer (minimised window)");
  VkSurfaceCapabilitiesKHR caps{};
  VK_CHECK(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(device_.physical_device(), surface_, &caps));
  if ((caps.supportedUsageFlags & desc_.usage) != desc_.usage)
    throw RuntimeError(
        fmt::format("swapchain: surface supports image usage 0x{:x}, the present pass needs 0x{:x}",
                    caps.supportedUsageFlags, desc_.usage));
  // currentExtent is the window's size unless the surface lets the swapchain decide (0xFFFFFFFF).
  if (caps.currentExtent.width != UINT32_MAX) {
    extent_ = caps.currentExtent;
  } else {
    extent_.width =
        std::clamp(framebuffer.width, caps.minImageExtent.width, caps.maxImageExtent.width);
    extent_.height =
        std::clamp(framebuffer.height, caps.minImageExtent.height, caps.maxImageExtent.height);
  }
  if (extent_.width == 0 || extent_.height == 0)
    throw RuntimeError("swapchain: the surface reports a 0 x 0 extent (minimised window)");
  std::uint32_t count = std::max(desc_.min_images, caps.minImageCount);
  if (caps.maxImageCount != 0) count = std::min(count, caps.maxImageCount);

  VkSwapchainCreateInfoKHR info{VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR};
  info.surface = surface_;
  info.minImageCount = count;
  info.imageFormat = format_;
  info.imageColorSpace = color_space_;
  info.imageExtent = extent_;
  info.imageArrayLayers = 1;
  info.imageUsage = desc_.usage;
  info.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
  info.preTransform = caps.currentTransform;
  info.compositeAlpha = (caps.supportedCompositeAlpha & VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR) != 0
                            ? VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR
                            : VK_COMPOSITE_ALPHA_INHERIT_BIT_KHR;
  info.presentMode = to_vk(present_mode_);
  info.clipped = VK_TRUE;
  info.oldSwapchain = old;
  VK_CHECK(vkCreateSwapchainKHR(device_.handle(), &info, nullptr, &swapchain_));
  ++generation_;
  device_.set_object_name(VK_OBJECT_TYPE_SWAPCHAIN_KHR, reinterpret_cast<std::uint64_t>(swapchain_),
                          fmt::format("swapchain.{}", generation_));

  const auto vk_images = enumerate<VkImage>([&](std::uint32_t* n, VkImage* p) {
    return vkGetSwapchainImagesKHR(device_.handle(), swapchain_, n, p);
  });
  images_.clear();
  for (std::uint32_t i = 0; i < vk_images.size(); ++i) {
    SwapchainImage image;
    image.image = vk_images[i];
    VkImageViewCreateInfo view{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    view.image = image.image;
    view.viewType = VK_IMAGE_VIEW_TYPE_2D;
    view.format = format_;
    view.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    VK_CHECK(vkCreateImageView(device_.handle(), &view, nullptr, &image.view));
    images_.push_back(image);
    device_.set_name(image.image, fmt::format("swapchain.image{}", i));
  }
  // Render-finished semaphores are kept across recreation (a present may still wait on one).
  while (render_finished_.size() < images_.size()) {
    VkSemaphoreCreateInfo semaphore_info{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    VkSemaphore semaphore = VK_NULL_HANDLE;
    VK_CHECK(vkCreateSemaphore(device_.handle(), &semaphore_info, nullptr, &semaphore));
    render_finished_.push_back(semaphore);
  }
  log::debug("swapchain {}: {}x{}, {} images, format {}, present mode {}", generation_,
             extent_.width, extent_.height, images_.size(), static_cast<int>(format_),
             present_mode_name(present_mode_));
}

void Swapchain::destroy_views() {
  for (auto& image : images_) vkDestroyImageView(device_.handle(), image.view, nullptr);
  images_.clear();
}

SwapchainStatus Swapchain::acquire(VkSemaphore signal, std::uint32_t* index) {
  const VkResult result = vkAcquireNextImageKHR(device_.handle(), swapchain_, UINT64_MAX, signal,
                                                VK_NULL_HANDLE, index);
  if (result == VK_ERROR_OUT_OF_DATE_KHR) return SwapchainStatus::OutOfDate;
  VK_CHECK(result);
  return result == VK_SUBOPTIMAL_KHR ? SwapchainStatus::Suboptimal : SwapchainStatus::Ok;
}

SwapchainStatus Swapchain::present(std::uint32_t index, VkSemaphore wait) {
  VkPresentInfoKHR info{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
  info.waitSemaphoreCount = 1;
  info.pWaitSemaphores = &wait;
  info.swapchainCount = 1;
  info.pSwapchains = &swapchain_;
  info.pImageIndices = &index;
  const VkResult result = vkQueuePresentKHR(device_.queue(), &info);
  images_.at(index).layout = VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;
  if (result == VK_ERROR_OUT_OF_DATE_KHR) return SwapchainStatus::OutOfDate;
  VK_CHECK(result);
  return result == VK_SUBOPTIMAL_KHR ? SwapchainStatus::Suboptimal : SwapchainStatus::Ok;
}

graph::ImportInfo Swapchain::import_info(VkPipelineStageFlags2 acquire_wait_stage) const {
  graph::ImportInfo info;
  info.initial = {acquire_wait_stage, VK_ACCESS_2_NONE, VK_IMAGE_LAYOUT_UNDEFINED};
  info.final = graph::AccessState{VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE,
                                  VK_IMAGE_LAYOUT_PRESENT_SRC_KHR};
  return info;
}

}  // namespace lantern::runtime
