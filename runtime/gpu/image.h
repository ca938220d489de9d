// RAII 2D VkImage (optimal tiling, device-local) with its full view. Move-only; named. Layout
// tracking belongs to the render graph; Image only remembers the format and extent.
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>
#include <string>

#include "runtime/gpu/memory_allocator.h"

namespace lantern::runtime {

class Device;

struct ImageDesc {
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  VkFormat format = VK_FORMAT_R32G32B32A32_SFLOAT;
  VkImageUsageFlags usage = 0;  // transfer src/dst are always added (uploads, readback)
  std::string name;
};

class Image {
 public:
  Image() = default;
  Image(Device& device, const ImageDesc& desc);
  ~Image();
  Image(Image&& other) noexcept;
  Image& operator=(Image&& other) noexcept;
  Image(const Image&) = delete;
  Image& operator=(const Image&) = delete;

  VkImage handle() const { return image_; }
  VkImageView view() const { return view_; }
  VkFormat format() const { return format_; }
  VkExtent2D extent() const { return extent_; }
  VkImageAspectFlags aspect() const { return aspect_; }
  const std::string& name() const { return name_; }
  explicit operator bool() const { return image_ != VK_NULL_HANDLE; }

 private:
  void release();

  Device* device_ = nullptr;
  VkImage image_ = VK_NULL_HANDLE;
  VkImageView view_ = VK_NULL_HANDLE;
  Allocation allocation_;
  VkFormat format_ = VK_FORMAT_UNDEFINED;
  VkExtent2D extent_{};
  VkImageAspectFlags aspect_ = VK_IMAGE_ASPECT_COLOR_BIT;
  std::string name_;
};

// Depth/stencil formats get depth (and stencil) aspects; everything else colour.
VkImageAspectFlags aspect_of(VkFormat format);
// Bytes per texel of an uncompressed colour or depth format; throws for unsupported formats.
std::uint32_t texel_size(VkFormat format);

}  // namespace lantern::runtime
