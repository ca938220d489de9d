// RAII VkBufferView: a typed view of a Buffer for texel-buffer descriptors (samplerBuffer,
// usamplerBuffer, imageBuffer), bound with Bindings::texel_buffer. The buffer needs
// VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT (or STORAGE_TEXEL) and must outlive the view.
#pragma once

#include <vulkan/vulkan.h>

#include <string_view>

namespace lantern::runtime {

class Device;
class Buffer;

class BufferView {
 public:
  BufferView() = default;
  // Whole buffer as `format` texels. Throws lantern::RuntimeError when the element count exceeds
  // the device's maxTexelBufferElements.
  BufferView(Device& device, const Buffer& buffer, VkFormat format, std::string_view name);
  // The first `size` bytes of `buffer` (a buffer the caller created), the same way.
  BufferView(Device& device, VkBuffer buffer, VkDeviceSize size, VkFormat format,
             std::string_view name);
  ~BufferView();
  BufferView(BufferView&& other) noexcept;
  BufferView& operator=(BufferView&& other) noexcept;
  BufferView(const BufferView&) = delete;
  BufferView& operator=(const BufferView&) = delete;

  VkBufferView handle() const { return view_; }
  explicit operator bool() const { return view_ != VK_NULL_HANDLE; }

 private:
  Device* device_ = nullptr;
  VkBufferView view_ = VK_NULL_HANDLE;
};

}  // namespace lantern::runtime
