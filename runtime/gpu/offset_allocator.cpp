// Best-fit free-list offset allocator.
#include "runtime/gpu/offset_allocator.h"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

namespace lantern::runtime {
namespace {
std::uint64_t align_up(std::uint64_t value, std::uint64_t alignment) {
  return (value + alignment - 1) & ~(alignment - 1);
}
}  // namespace

OffsetAllocator::OffsetAllocator(std::uint64_t capacity) : capacity_(capacity) {
  if (capacity > 0) free_.emplace(0, capacity);
}

std::optional<std::uint64_t> OffsetAllocator::allocate(std::uint64_t size,
                                                       std::uint64_t alignment) {
  if (alignment == 0) alignment = 1;
  if ((alignment & (alignment - 1)) != 0)
    throw std::logic_error(
        fmt::format("OffsetAllocator: alignment {} is not a power of two", alignment));
  if (size == 0) size = 1;  // distinct offsets for zero-sized requests

  auto best = free_.end();
  std::uint64_t best_size = 0;
  for (auto it = free_.begin(); it != free_.end(); ++it) {
    const std::uint64_t start = align_up(it->first, alignment);
    const std::uint64_t end = it->first + it->second;
    if (start + size <= end && (best == free_.end() || it->second < best_size)) {
      best = it;
      best_size = it->second;
      if (best_size == size) break;  // exact fit
    }
  }
  if (best == free_.end()) return std::nullopt;

  const std::uint64_t range_offset = best->first;
  const std::uint64_t range_end = best->first + best->second;
  const std::uint64_t offset = align_up(range_offset, alignment);
  free_.erase(best);
  if (offset > range_offset) free_.emplace(range_offset, offset - range_offset);  // alignment gap
  if (offset + size < range_end) free_.emplace(offset + size, range_end - (offset + size));
  allocated_.emplace(offset, size);
  used_ += size;
  return offset;
}

void OffsetAllocator::free(std::uint64_t offset) {
  const auto it = allocated_.find(offset);
  if (it == allocated_.end())
    throw std::logic_error(fmt::format("OffsetAllocator: free of unknown offset {}", offset));
  const std::uint64_t size = it->second;
  allocated_.erase(it);
  used_ -= size;
  insert_free(offset, size);
}

void OffsetAllocator::insert_free(std::uint64_t offset, std::uint64_t size) {
  auto next = free_.lower_bound(offset);
  if (next != free_.end() && offset + size == next->first) {  // merge with the range after
    size += next->second;
    next = free_.erase(next);
  }
  if (next != free_.begin()) {
    auto prev = std::prev(next);
    if (prev->first + prev->second == offset) {  // merge with the range before
      prev->second += size;
      return;
    }
  }
  free_.emplace(offset, size);
}

std::uint64_t OffsetAllocator::largest_free_range() const {
  std::uint64_t largest = 0;
  for (const auto& [offset, size] : free_) largest = std::max(largest, size);
  return largest;
}

}  // namespace lantern::runtime
