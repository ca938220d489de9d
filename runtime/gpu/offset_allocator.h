// A pure offset allocator over [0, capacity): best-fit on a free list of ranges, alignment-aware,
// coalescing on free. No Vulkan: MemoryAllocator places resources in VkDeviceMemory blocks with
// it, and it is unit-tested on the CPU.
#pragma once

#include <cstdint>
#include <map>
#include <optional>

namespace lantern::runtime {

class OffsetAllocator {
 public:
  explicit OffsetAllocator(std::uint64_t capacity);

  // Offset of a new range of `size` bytes aligned to `alignment` (a power of two), or nullopt when
  // no free range fits. Best fit: the smallest free range that holds the aligned request.
  std::optional<std::uint64_t> allocate(std::uint64_t size, std::uint64_t alignment);
  // Frees a range returned by allocate(). Throws std::logic_error for an unknown offset.
  void free(std::uint64_t offset);

  std::uint64_t capacity() const { return capacity_; }
  std::uint64_t used() const { return used_; }  // bytes in live allocations (padding excluded)
  std::uint64_t largest_free_range() const;
  std::size_t free_range_count() const { return free_.size(); }
  std::size_t allocation_count() const { return allocated_.size(); }
  bool empty() const { return allocated_.empty(); }

 private:
  void insert_free(std::uint64_t offset, std::uint64_t size);  // coalesces with neighbours

  std::uint64_t capacity_;
  std::uint64_t used_ = 0;
  std::map<std::uint64_t, std::uint64_t> free_;       // offset -> size, disjoint, non-adjacent
  std::map<std::uint64_t, std::uint64_t> allocated_;  // offset -> size
};

}  // namespace lantern::runtime
