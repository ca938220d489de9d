// One-shot uploads and readbacks between host memory and Buffers/Images. Host-visible buffers are
// written/read through their mapping; everything else goes through a staging buffer and
// Device::submit_and_wait. These block: use them for setup, tests and captures, not per frame.
#pragma once

#include <vulkan/vulkan.h>

#include <cstddef>
#include <cstring>
#include <span>
#include <vector>

#include "runtime/gpu/buffer.h"
#include "runtime/gpu/image.h"

namespace lantern::runtime {

class Device;

void upload_buffer(Device& device, Buffer& dst, std::span<const std::byte> data,
                   VkDeviceSize offset = 0);
std::vector<std::byte> read_buffer_bytes(Device& device, const Buffer& src);

template <class T>
void upload_buffer(Device& device, Buffer& dst, std::span<const T> values,
                   VkDeviceSize offset = 0) {
  upload_buffer(device, dst, std::as_bytes(values), offset);
}

template <class T>
std::vector<T> read_buffer(Device& device, const Buffer& src) {
  const std::vector<std::byte> bytes = read_buffer_bytes(device, src);
  std::vector<T> values(bytes.size() / sizeof(T));
  std::memcpy(values.data(), bytes.data(), values.size() * sizeof(T));
  return values;
}

// Uploads tightly packed texels (width * height * texel_size bytes) and leaves the image in
// `final_layout`. Previous contents are discarded.
void upload_image(Device& device, Image& dst, std::span<const std::byte> texels,
                  VkImageLayout final_layout);
// Reads the whole image as tightly packed rows; the image is in `layout` before and after.
std::vector<std::byte> read_image(Device& device, const Image& src, VkImageLayout layout);

// Records a full-image layout transition (synchronization2, conservative ALL_COMMANDS scopes).
// For one-shot helpers only: frame work gets its barriers from the render graph.
void transition_image(Device& device, VkCommandBuffer cmd, const Image& image, VkImageLayout from,
                      VkImageLayout to);

}  // namespace lantern::runtime
