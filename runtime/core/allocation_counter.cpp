// AllocationCounter (allocation_counter.h). Each block carries a header just below the pointer
// handed out: the requested size, the scope, and the offset back to the start of the malloc block.
#include "runtime/core/allocation_counter.h"

#include <algorithm>
#include <cstddef>
#include <cstdlib>
#include <cstring>

namespace lantern::runtime {
namespace {

struct Header {
  std::size_t size;
  std::size_t offset;  // from the malloc block to the user pointer
  VkSystemAllocationScope scope;
};

Header* header_of(void* memory) {
  return reinterpret_cast<Header*>(static_cast<char*>(memory) - sizeof(Header));
}

}  // namespace

AllocationCounter::AllocationCounter() {
  callbacks_.pUserData = this;
  callbacks_.pfnAllocation = &AllocationCounter::allocate;
  callbacks_.pfnReallocation = &AllocationCounter::reallocate;
  callbacks_.pfnFree = &AllocationCounter::release;
}

AllocationCounts AllocationCounter::live() const {
  AllocationCounts counts;
  counts.object = live_[VK_SYSTEM_ALLOCATION_SCOPE_OBJECT].load();
  for (const auto& n : live_) counts.total += n.load();
  counts.bytes = bytes_.load();
  return counts;
}

void* AllocationCounter::allocate(std::size_t size, std::size_t alignment,
                                  VkSystemAllocationScope scope) {
  if (size == 0) return nullptr;
  alignment = std::max<std::size_t>(alignment, alignof(std::max_align_t));
  // Room for the header below an aligned user pointer.
  const std::size_t offset = (sizeof(Header) + alignment - 1) / alignment * alignment;
  char* block = static_cast<char*>(std::malloc(offset + size + alignment));
  if (block == nullptr) return nullptr;
  const auto base = reinterpret_cast<std::uintptr_t>(block) + offset;
  char* user = reinterpret_cast<char*>((base + alignment - 1) / alignment * alignment);
  *header_of(user) = Header{size, static_cast<std::size_t>(user - block), scope};
  const auto index = static_cast<std::size_t>(scope) < kScopes ? scope : 0;
  live_[index].fetch_add(1);
  bytes_.fetch_add(static_cast<std::int64_t>(size));
  return user;
}

void AllocationCounter::release(void* memory) {
  if (memory == nullptr) return;
  const Header h = *header_of(memory);
  const auto index = static_cast<std::size_t>(h.scope) < kScopes ? h.scope : 0;
  live_[index].fetch_sub(1);
  bytes_.fetch_sub(static_cast<std::int64_t>(h.size));
  std::free(static_cast<char*>(memory) - h.offset);
}

void* VKAPI_PTR AllocationCounter::allocate(void* user, std::size_t size, std::size_t alignment,
                                            VkSystemAllocationScope scope) {
  return static_cast<AllocationCounter*>(user)->allocate(size, alignment, scope);
}

void* VKAPI_PTR AllocationCounter::reallocate(void* user, void* original, std::size_t size,
                                              std::size_t alignment,
                                              VkSystemAllocationScope scope) {
  auto* self = static_cast<AllocationCounter*>(user);
  if (original == nullptr) return self->allocate(size, alignment, scope);
  if (size == 0) {
    self->release(original);
    return nullptr;
  }
  void* moved = self->allocate(size, alignment, scope);
  if (moved == nullptr) return nullptr;  // the original stays valid, as the spec requires
  std::memcpy(moved, original, std::min(size, header_of(original)->size));
  self->release(original);
  return moved;
}

void VKAPI_PTR AllocationCounter::release(void* user, void* memory) {
  static_cast<AllocationCounter*>(user)->release(memory);
}

}  // namespace lantern::runtime
