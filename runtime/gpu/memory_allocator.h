// Device memory sub-allocation: big VkDeviceMemory blocks (64 MiB by default) per memory type and
// resource kind, carved with OffsetAllocator; resources larger than half a block get their own
// allocation. Host-visible blocks stay persistently mapped. Linear resources (buffers) and
// optimal-tiling images never share a block, so bufferImageGranularity can never be violated.
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace lantern::runtime {

enum class MemoryUsage {
  DeviceLocal,  // GPU-only data; may still be host-visible (lavapipe, UMA) and then gets mapped
  Upload,       // host writes, GPU reads: host-visible + coherent, device-local preferred
  Readback,     // GPU writes, host reads: host-visible + coherent, cached preferred
};

enum class ResourceKind { Linear, OptimalImage };

struct Allocation {
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkDeviceSize offset = 0;
  VkDeviceSize size = 0;
  std::byte* mapped = nullptr;  // non-null when host-visible
  std::uint32_t memory_type = 0;
  void* block = nullptr;  // owner block (opaque); null for a dedicated allocation
  explicit operator bool() const { return memory != VK_NULL_HANDLE; }
};

struct HeapStats {
  std::uint32_t heap = 0;
  VkDeviceSize heap_size = 0;
  bool device_local = false;
  VkDeviceSize reserved = 0;  // bytes in VkDeviceMemory objects on this heap
  VkDeviceSize used = 0;      // bytes handed to resources
  std::uint32_t blocks = 0;   // VkDeviceMemory objects (blocks + dedicated)
  std::uint32_t allocations = 0;
};

// "heap 0 (device-local, 23.5 GiB): 64.0 MiB reserved in 1 block(s), 3.2 MiB used by 12
// allocation(s)" per heap that holds memory, for `lantern info` and logs.
std::string describe(const std::vector<HeapStats>& heaps);

class MemoryAllocator {
 public:
  struct Options {
    VkDeviceSize block_size = 64ull << 20;
    bool device_address = false;   // allocate with VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT
    bool map_device_local = true;  // false: DeviceLocal allocations never expose a host pointer
  };
  MemoryAllocator(VkDevice device, const VkPhysicalDeviceMemoryProperties& properties,
                  Options options);
  ~MemoryAllocator();
  MemoryAllocator(const MemoryAllocator&) = delete;
  MemoryAllocator& operator=(const MemoryAllocator&) = delete;

  // Throws lantern::RuntimeError when no memory type fits or the device is out of memory.
  Allocation allocate(const VkMemoryRequirements& requirements, MemoryUsage usage,
                      ResourceKind kind);
  void free(const Allocation& allocation);

  std::vector<HeapStats> stats() const;
  // Index of the memory type chosen for `usage` among `type_bits`, or -1.
  int find_memory_type(std::uint32_t type_bits, MemoryUsage usage) const;
  VkDeviceSize block_size() const { return options_.block_size; }

 private:
  struct Block;
  VkDeviceMemory allocate_memory(VkDeviceSize size, std::uint32_t type, std::byte** mapped);

  VkDevice device_;
  VkPhysicalDeviceMemoryProperties properties_;
  Options options_;
  mutable std::mutex mutex_;
  std::vector<std::unique_ptr<Block>> blocks_;
  std::vector<HeapStats> dedicated_;  // per heap: dedicated allocations
};

}  // namespace lantern::runtime
