// AllocationCounter: VkAllocationCallbacks that count the driver's live host allocations, by
// allocation scope. Given to vkCreateDevice (DeviceOptions::count_driver_allocations), it becomes
// the allocator of every object created from that device with pAllocator = nullptr, so the live
// OBJECT-scope count rises by at least one per live Vulkan object (buffer, image, view, pipeline,
// descriptor pool, fence, acceleration structure, ...) and a leak of any of them shows as growth.
// Thread-safe (drivers allocate from their own threads); alignment as the driver asks.
#pragma once

#include <vulkan/vulkan.h>

#include <array>
#include <atomic>
#include <cstdint>

namespace lantern::runtime {

struct AllocationCounts {
  std::int64_t object = 0;  // live allocations in VK_SYSTEM_ALLOCATION_SCOPE_OBJECT
  std::int64_t total = 0;   // live allocations in every scope
  std::int64_t bytes = 0;   // their requested bytes
};

class AllocationCounter {
 public:
  AllocationCounter();
  AllocationCounter(const AllocationCounter&) = delete;
  AllocationCounter& operator=(const AllocationCounter&) = delete;

  const VkAllocationCallbacks* callbacks() const { return &callbacks_; }
  AllocationCounts live() const;

 private:
  static void* VKAPI_PTR allocate(void* user, std::size_t size, std::size_t alignment,
                                  VkSystemAllocationScope scope);
  static void* VKAPI_PTR reallocate(void* user, void* original, std::size_t size,
                                    std::size_t alignment, VkSystemAllocationScope scope);
  static void VKAPI_PTR release(void* user, void* memory);

  void* allocate(std::size_t size, std::size_t alignment, VkSystemAllocationScope scope);
  void release(void* memory);

  static constexpr std::size_t kScopes = VK_SYSTEM_ALLOCATION_SCOPE_INSTANCE + 1;
  std::array<std::atomic<std::int64_t>, kScopes> live_{};
  std::atomic<std::int64_t> bytes_{0};
  VkAllocationCallbacks callbacks_{};
};

}  // namespace lantern::runtime
