// Buffer creation and lifetime.
#include "runtime/gpu/buffer.h"

#include <fmt/format.h>

#include <utility>

#include "engine/core/error.h"
#include "runtime/core/device.h"
#include "runtime/core/vk_check.h"

namespace lantern::runtime {

Buffer::Buffer(Device& device, const BufferDesc& desc)
    : device_(&device), size_(desc.size), name_(desc.name) {
  if (desc.size == 0) throw RuntimeError(fmt::format("buffer '{}': size must be > 0", desc.name));
  VkBufferUsageFlags usage =
      desc.usage | VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
  if (!device.caps().buffer_device_address) usage &= ~VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT;
  VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  info.size = desc.size;
  info.usage = usage;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  VK_CHECK(vkCreateBuffer(device.handle(), &info, nullptr, &buffer_));
  VkMemoryRequirements requirements{};
  vkGetBufferMemoryRequirements(device.handle(), buffer_, &requirements);
  try {
    allocation_ = device.memory().allocate(requirements, desc.memory, ResourceKind::Linear);
  } catch (...) {
    vkDestroyBuffer(device.handle(), buffer_, nullptr);
    throw;
  }
  VK_CHECK(vkBindBufferMemory(device.handle(), buffer_, allocation_.memory, allocation_.offset));
  if ((usage & VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT) != 0) {
    VkBufferDeviceAddressInfo address{VK_STRUCTURE_TYPE_BUFFER_DEVICE_ADDRESS_INFO};
    address.buffer = buffer_;
    address_ = vkGetBufferDeviceAddress(device.handle(), &address);
  }
  if (!name_.empty()) device.set_name(buffer_, name_);
}

Buffer::~Buffer() {
  release();
}

Buffer::Buffer(Buffer&& other) noexcept {
  *this = std::move(other);
}

Buffer& Buffer::operator=(Buffer&& other) noexcept {
  if (this != &other) {
    release();
    device_ = std::exchange(other.device_, nullptr);
    buffer_ = std::exchange(other.buffer_, VK_NULL_HANDLE);
    allocation_ = std::exchange(other.allocation_, Allocation{});
    size_ = std::exchange(other.size_, 0);
    address_ = std::exchange(other.address_, 0);
    name_ = std::move(other.name_);
  }
  return *this;
}

void Buffer::release() {
  if (buffer_ == VK_NULL_HANDLE) return;
  vkDestroyBuffer(device_->handle(), buffer_, nullptr);
  device_->memory().free(allocation_);
  buffer_ = VK_NULL_HANDLE;
}

}  // namespace lantern::runtime
