// Image creation and lifetime.
#include "runtime/gpu/image.h"

#include <fmt/format.h>

#include <utility>

#include "engine/core/error.h"
#include "runtime/core/device.h"
#include "runtime/core/vk_check.h"

namespace lantern::runtime {

VkImageAspectFlags aspect_of(VkFormat format) {
  switch (format) {
    case VK_FORMAT_D16_UNORM:
    case VK_FORMAT_D32_SFLOAT:
    case VK_FORMAT_X8_D24_UNORM_PACK32:
      return VK_IMAGE_ASPECT_DEPTH_BIT;
    case VK_FORMAT_D24_UNORM_S8_UINT:
    case VK_FORMAT_D32_SFLOAT_S8_UINT:
    case VK_FORMAT_D16_UNORM_S8_UINT:
      return VK_IMAGE_ASPECT_DEPTH_BIT | VK_IMAGE_ASPECT_STENCIL_BIT;
    default:
      return VK_IMAGE_ASPECT_COLOR_BIT;
  }
}

std::uint32_t texel_size(VkFormat format) {
  switch (format) {
    case VK_FORMAT_R8_UNORM:
    case VK_FORMAT_R8_UINT:
      return 1;
    case VK_FORMAT_R16_SFLOAT:
    case VK_FORMAT_R16_UINT:
    case VK_FORMAT_R8G8_UNORM:
    case VK_FORMAT_D16_UNORM:
      return 2;
    case VK_FORMAT_R8G8B8A8_UNORM:
    case VK_FORMAT_R8G8B8A8_SRGB:
    case VK_FORMAT_B8G8R8A8_UNORM:
    case VK_FORMAT_B8G8R8A8_SRGB:
    case VK_FORMAT_R32_SFLOAT:
    case VK_FORMAT_R32_UINT:
    case VK_FORMAT_R16G16_SFLOAT:
    case VK_FORMAT_A2B10G10R10_UNORM_PACK32:
    case VK_FORMAT_B10G11R11_UFLOAT_PACK32:
    case VK_FORMAT_D32_SFLOAT:
    case VK_FORMAT_X8_D24_UNORM_PACK32:
      return 4;
    case VK_FORMAT_R16G16B16A16_SFLOAT:
    case VK_FORMAT_R32G32_SFLOAT:
    case VK_FORMAT_R32G32_UINT:
      return 8;
    case VK_FORMAT_R32G32B32A32_SFLOAT:
    case VK_FORMAT_R32G32B32A32_UINT:
    case VK_FORMAT_R32G32B32A32_SINT:
      return 16;
    default:
      throw RuntimeError(
          fmt::format("texel_size: unsupported VkFormat {}", static_cast<int>(format)));
  }
}

Image::Image(Device& device, const ImageDesc& desc)
    : device_(&device),
      format_(desc.format),
      extent_{desc.width, desc.height},
      aspect_(aspect_of(desc.format)),
      name_(desc.name) {
  if (desc.width == 0 || desc.height == 0)
    throw RuntimeError(fmt::format("image '{}': extent {}x{} must be non-zero", desc.name,
                                   desc.width, desc.height));
  VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  info.imageType = VK_IMAGE_TYPE_2D;
  info.format = desc.format;
  info.extent = {desc.width, desc.height, 1};
  info.mipLevels = 1;
  info.arrayLayers = 1;
  info.samples = VK_SAMPLE_COUNT_1_BIT;
  info.tiling = VK_IMAGE_TILING_OPTIMAL;
  info.usage = desc.usage | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  VK_CHECK(vkCreateImage(device.handle(), &info, nullptr, &image_));
  VkMemoryRequirements requirements{};
  vkGetImageMemoryRequirements(device.handle(), image_, &requirements);
  try {
    allocation_ = device.memory().allocate(requirements, MemoryUsage::DeviceLocal,
                                           ResourceKind::OptimalImage);
  } catch (...) {
    vkDestroyImage(device.handle(), image_, nullptr);
    throw;
  }
  VK_CHECK(vkBindImageMemory(device.handle(), image_, allocation_.memory, allocation_.offset));

  VkImageViewCreateInfo view{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
  view.image = image_;
  view.viewType = VK_IMAGE_VIEW_TYPE_2D;
  view.format = desc.format;
  view.subresourceRange = {aspect_, 0, 1, 0, 1};
  VK_CHECK(vkCreateImageView(device.handle(), &view, nullptr, &view_));
  if (!name_.empty()) {
    device.set_name(image_, name_);
    device.set_name(view_, name_ + ".view");
  }
}

Image::~Image() {
  release();
}

Image::Image(Image&& other) noexcept {
  *this = std::move(other);
}

Image& Image::operator=(Image&& other) noexcept {
  if (this != &other) {
    release();
    device_ = std::exchange(other.device_, nullptr);
    image_ = std::exchange(other.image_, VK_NULL_HANDLE);
    view_ = std::exchange(other.view_, VK_NULL_HANDLE);
    allocation_ = std::exchange(other.allocation_, Allocation{});
    format_ = other.format_;
    extent_ = other.extent_;
    aspect_ = other.aspect_;
    name_ = std::move(other.name_);
  }
  return *this;
}

void Image::release() {
  if (image_ == VK_NULL_HANDLE) return;
  vkDestroyImageView(device_->handle(), view_, nullptr);
  vkDestroyImage(device_->handle(), image_, nullptr);
  device_->memory().free(allocation_);
  image_ = VK_NULL_HANDLE;
}

}  // namespace lantern::runtime
