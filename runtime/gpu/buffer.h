// RAII VkBuffer placed in sub-allocated memory. Move-only; named for debuggers and validation.
#pragma once

#include <vulkan/vulkan.h>

#include <cstddef>
#include <string>

#include "runtime/gpu/memory_allocator.h"

namespace lantern::runtime {

class Device;

struct BufferDesc {
  VkDeviceSize size = 0;
  VkBufferUsageFlags usage = 0;  // transfer src/dst are always added (uploads, readback)
  MemoryUsage memory = MemoryUsage::DeviceLocal;
  std::string name;
};

class Buffer {
 public:
  Buffer() = default;
  Buffer(Device& device, const BufferDesc& desc);
  ~Buffer();
  Buffer(Buffer&& other) noexcept;
  Buffer& operator=(Buffer&& other) noexcept;
  Buffer(const Buffer&) = delete;
  Buffer& operator=(const Buffer&) = delete;

  VkBuffer handle() const { return buffer_; }
  VkDeviceSize size() const { return size_; }
  const std::string& name() const { return name_; }
  // Host pointer when the memory is host-visible (always for Upload/Readback), else nullptr.
  std::byte* mapped() const { return allocation_.mapped; }
  // GPU address (0 unless the device has buffer device address and usage asked for it).
  VkDeviceAddress device_address() const { return address_; }
  explicit operator bool() const { return buffer_ != VK_NULL_HANDLE; }

 private:
  void release();

  Device* device_ = nullptr;
  VkBuffer buffer_ = VK_NULL_HANDLE;
  Allocation allocation_;
  VkDeviceSize size_ = 0;
  VkDeviceAddress address_ = 0;
  std::string name_;
};

}  // namespace lantern::runtime
