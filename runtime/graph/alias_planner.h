// Places transient resources in one memory block so that resources whose lifetimes (first..last
// pass in execution order) do not overlap may share bytes. Pure data: sizes come from the device
// when there is one, from estimates otherwise.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace lantern::runtime::graph {

struct AliasRequest {
  uint64_t size = 0;
  uint64_t alignment = 1;
  uint32_t first_pass = 0;  // position in execution order
  uint32_t last_pass = 0;
};

struct AliasPlan {
  std::vector<uint64_t> offsets;  // one per request, into the shared block
  uint64_t block_size = 0;        // bytes the shared block needs
  uint64_t unaliased_size = 0;    // bytes without aliasing (placed one after another)
  [[nodiscard]] uint64_t saved() const { return unaliased_size - block_size; }
};

// Greedy placement, biggest first, each at the lowest offset free for its whole lifetime.
[[nodiscard]] AliasPlan plan_aliasing(std::span<const AliasRequest> requests);

// True when a and b share bytes in `plan` (both placed, ranges overlap).
[[nodiscard]] bool memory_overlaps(const AliasPlan& plan, std::span<const AliasRequest> requests,
                                   size_t a, size_t b);

}  // namespace lantern::runtime::graph
