// Buffer views (buffer_view.h).
#include "runtime/gpu/buffer_view.h"

#include <fmt/format.h>

#include <cstdint>
#include <utility>

#include "engine/core/error.h"
#include "runtime/core/device.h"
#include "runtime/core/vk_check.h"
#include "runtime/gpu/buffer.h"
#include "runtime/gpu/image.h"

namespace lantern::runtime {
BufferView::BufferView(Device& device, const Buffer& buffer, VkFormat format, std::string_view name)
    : BufferView(device, buffer.handle(), buffer.size(), format, name) {}

BufferView::BufferView(Device& device, VkBuffer buffer, VkDeviceSize size, VkFormat format,
                       std::string_view name)
    : device_(&device) {
  const VkDeviceSize texel = texel_size(format);  // throws for a format it does not know
  const VkDeviceSize elements = size / texel;
  if (elements > device.properties().limits.maxTexelBufferElements)
    throw RuntimeError(
        fmt::format("buffer view '{}': {} texels exceed the device's maxTexelBufferElements ({})",
                    name, elements, device.properties().limits.maxTexelBufferElements));
  VkBufferViewCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_VIEW_CREATE_INFO};
  info.buffer = buffer;
  info.format = format;
  info.offset = 0;
  info.range = elements * texel;
  VK_CHECK(vkCreateBufferView(device.handle(), &info, nullptr, &view_));
  device.set_object_name(VK_OBJECT_TYPE_BUFFER_VIEW, reinterpret_cast<std::uint64_t>(view_), name);
}

BufferView::~BufferView() {
  if (view_ != VK_NULL_HANDLE) vkDestroyBufferView(device_->handle(), view_, nullptr);
}

BufferView::BufferView(BufferView&& other) noexcept
    : device_(std::exchange(other.device_, nullptr)),
      view_(std::exchange(other.view_, VK_NULL_HANDLE)) {}

BufferView& BufferView::operator=(BufferView&& other) noexcept {
  if (this != &other) {
    if (view_ != VK_NULL_HANDLE) vkDestroyBufferView(device_->handle(), view_, nullptr);
    device_ = std::exchange(other.device_, nullptr);
    view_ = std::exchange(other.view_, VK_NULL_HANDLE);
  }
  return *this;
}

}  // namespace lantern::runtime
