// Interval packing of transient resources over (lifetime × memory range).
#include "runtime/graph/alias_planner.h"

#include <algorithm>
#include <numeric>

namespace lantern::runtime::graph {

namespace {

uint64_t align_up(uint64_t value, uint64_t alignment) {
  return alignment <= 1 ? value : (value + alignment - 1) / alignment * alignment;
}

bool lifetimes_overlap(const AliasRequest& a, const AliasRequest& b) {
  return a.first_pass <= b.last_pass && b.first_pass <= a.last_pass;
}

}  // namespace

AliasPlan plan_aliasing(std::span<const AliasRequest> requests) {
  AliasPlan plan;
  plan.offsets.assign(requests.size(), 0);
  std::vector<size_t> order(requests.size());
  std::iota(order.begin(), order.end(), size_t{0});
  // Biggest first (ties: earlier first) keeps big blocks at low offsets and the result stable.
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t a, size_t b) { return requests[a].size > requests[b].size; });

  std::vector<size_t> placed;
  for (size_t index : order) {
    const AliasRequest& r = requests[index];
    plan.unaliased_size = align_up(plan.unaliased_size, r.alignment) + r.size;
    // Candidate offsets: 0 and the end of every placed resource alive at the same time; take the
    // lowest candidate that collides with none of them.
    std::vector<uint64_t> candidates{0};
    for (size_t other : placed)
      if (lifetimes_overlap(r, requests[other]))
        candidates.push_back(align_up(plan.offsets[other] + requests[other].size, r.alignment));
    std::sort(candidates.begin(), candidates.end());
    uint64_t chosen = candidates.back();
    for (uint64_t offset : candidates) {
      const bool free = std::none_of(placed.begin(), placed.end(), [&](size_t other) {
        const AliasRequest& o = requests[other];
        return lifetimes_overlap(r, o) && offset < plan.offsets[other] + o.size &&
               plan.offsets[other] < offset + r.size;
      });
      if (free) {
        chosen = offset;
        break;
      }
    }
    plan.offsets[index] = chosen;
    plan.block_size = std::max(plan.block_size, chosen + r.size);
    placed.push_back(index);
  }
  // Alignment padding can make the greedy layout lose to plain sequential placement; never
  // return a plan worse than not aliasing at all.
  if (plan.block_size > plan.unaliased_size) {
    uint64_t end = 0;
    for (size_t index : order) {
      plan.offsets[index] = align_up(end, requests[index].alignment);
      end = plan.offsets[index] + requests[index].size;
    }
    plan.block_size = plan.unaliased_size;
  }
  return plan;
}

bool memory_overlaps(const AliasPlan& plan, std::span<const AliasRequest> requests, size_t a,
                     size_t b) {
  return plan.offsets[a] < plan.offsets[b] + requests[b].size &&
         plan.offsets[b] < plan.offsets[a] + requests[a].size;
}

}  // namespace lantern::runtime::graph
