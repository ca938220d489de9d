// Block sub-allocator for VkDeviceMemory.
#include "runtime/gpu/memory_allocator.h"

#include <fmt/format.h>

#include <algorithm>

#include "engine/core/error.h"
#include "runtime/core/vk_check.h"
#include "runtime/gpu/offset_allocator.h"

namespace lantern::runtime {

struct MemoryAllocator::Block {
  VkDeviceMemory memory = VK_NULL_HANDLE;
  std::uint32_t type = 0;
  ResourceKind kind = ResourceKind::Linear;
  std::byte* mapped = nullptr;
  OffsetAllocator offsets;
  Block(VkDeviceMemory m, std::uint32_t t, ResourceKind k, std::byte* p, VkDeviceSize size)
      : memory(m), type(t), kind(k), mapped(p), offsets(size) {}
};

MemoryAllocator::MemoryAllocator(VkDevice device,
                                 const VkPhysicalDeviceMemoryProperties& properties,
                                 Options options)
    : device_(device), properties_(properties), options_(options) {
  dedicated_.resize(properties_.memoryHeapCount);
  // Small heaps (e.g. 256 MiB BAR) get smaller blocks so one block is not most of the heap.
  VkDeviceSize smallest_heap = ~VkDeviceSize{0};
  for (std::uint32_t h = 0; h < properties_.memoryHeapCount; ++h)
    smallest_heap = std::min(smallest_heap, properties_.memoryHeaps[h].size);
  options_.block_size =
      std::min(options_.block_size, std::max<VkDeviceSize>(smallest_heap / 8, 1 << 20));
}

MemoryAllocator::~MemoryAllocator() {
  for (auto& block : blocks_) {
    if (block->mapped != nullptr) vkUnmapMemory(device_, block->memory);
    vkFreeMemory(device_, block->memory, nullptr);
  }
}

int MemoryAllocator::find_memory_type(std::uint32_t type_bits, MemoryUsage usage) const {
  VkMemoryPropertyFlags required = 0;
  VkMemoryPropertyFlags preferred = 0;
  switch (usage) {
    case MemoryUsage::DeviceLocal:
      preferred = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
      break;
    case MemoryUsage::Upload:
      required = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
      preferred = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
      break;
    case MemoryUsage::Readback:
      required = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
      preferred = VK_MEMORY_PROPERTY_HOST_CACHED_BIT;
      break;
  }
  int best = -1;
  int best_score = -1;
  for (std::uint32_t t = 0; t < properties_.memoryTypeCount; ++t) {
    const VkMemoryPropertyFlags flags = properties_.memoryTypes[t].propertyFlags;
    if ((type_bits & (1u << t)) == 0 || (flags & required) != required) continue;
    const int score = __builtin_popcount(flags & preferred);
    if (score > best_score) {
      best = static_cast<int>(t);
      best_score = score;
    }
  }
  return best;
}

VkDeviceMemory MemoryAllocator::allocate_memory(VkDeviceSize size, std::uint32_t type,
                                                std::byte** mapped) {
  VkMemoryAllocateFlagsInfo flags{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_FLAGS_INFO};
  flags.flags = VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT;
  VkMemoryAllocateInfo info{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  info.pNext = options_.device_address ? &flags : nullptr;
  info.allocationSize = size;
  info.memoryTypeIndex = type;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VK_CHECK(vkAllocateMemory(device_, &info, nullptr, &memory));
  *mapped = nullptr;
  if ((properties_.memoryTypes[type].propertyFlags & VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT) != 0) {
    void* pointer = nullptr;
    VK_CHECK(vkMapMemory(device_, memory, 0, VK_WHOLE_SIZE, 0, &pointer));
    *mapped = static_cast<std::byte*>(pointer);
  }
  return memory;
}

Allocation MemoryAllocator::allocate(const VkMemoryRequirements& req, MemoryUsage usage,
                                     ResourceKind kind) {
  const int type_index = find_memory_type(req.memoryTypeBits, usage);
  if (type_index < 0)
    throw RuntimeError(fmt::format("no Vulkan memory type fits usage {} (type bits {:#x})",
                                   static_cast<int>(usage), req.memoryTypeBits));
  const auto type = static_cast<std::uint32_t>(type_index);
  auto hide_mapping = [&](Allocation allocation) {
    if (usage == MemoryUsage::DeviceLocal && !options_.map_device_local)
      allocation.mapped = nullptr;
    return allocation;
  };
  std::lock_guard lock(mutex_);

  Allocation a;
  a.memory_type = type;
  a.size = req.size;
  if (req.size > options_.block_size / 2) {  // large: its own VkDeviceMemory
    a.memory = allocate_memory(req.size, type, &a.mapped);
    HeapStats& s = dedicated_[properties_.memoryTypes[type].heapIndex];
    s.reserved += req.size;
    s.used += req.size;
    ++s.blocks;
    ++s.allocations;
    return hide_mapping(a);
  }
  for (auto& block : blocks_) {
    if (block->type != type || block->kind != kind) continue;
    if (auto offset = block->offsets.allocate(req.size, req.alignment)) {
      a.memory = block->memory;
      a.offset = *offset;
      a.mapped = block->mapped != nullptr ? block->mapped + *offset : nullptr;
      a.block = block.get();
      return hide_mapping(a);
    }
  }
  std::byte* mapped = nullptr;
  VkDeviceMemory memory = allocate_memory(options_.block_size, type, &mapped);
  auto& block = blocks_.emplace_back(
      std::make_unique<Block>(memory, type, kind, mapped, options_.block_size));
  const auto offset = block->offsets.allocate(req.size, req.alignment);
  LANTERN_ASSERT(offset.has_value());
  a.memory = memory;
  a.offset = *offset;
  a.mapped = mapped != nullptr ? mapped + *offset : nullptr;
  a.block = block.get();
  return hide_mapping(a);
}

void MemoryAllocator::free(const Allocation& a) {
  if (!a) return;
  std::lock_guard lock(mutex_);
  if (a.block == nullptr) {
    if (a.mapped != nullptr) vkUnmapMemory(device_, a.memory);
    vkFreeMemory(device_, a.memory, nullptr);
    HeapStats& s = dedicated_[properties_.memoryTypes[a.memory_type].heapIndex];
    s.reserved -= a.size;
    s.used -= a.size;
    --s.blocks;
    --s.allocations;
    return;
  }
  auto it = std::find_if(blocks_.begin(), blocks_.end(),
                         [&](const auto& b) { return b.get() == a.block; });
  LANTERN_ASSERT(it != blocks_.end());
  Block& block = **it;
  block.offsets.free(a.offset);
  // Release an empty block unless it is the last one of its type and kind (avoids churn).
  if (block.offsets.empty()) {
    const auto same = std::count_if(blocks_.begin(), blocks_.end(), [&](const auto& b) {
      return b->type == block.type && b->kind == block.kind;
    });
    if (same > 1) {
      if (block.mapped != nullptr) vkUnmapMemory(device_, block.memory);
      vkFreeMemory(device_, block.memory, nullptr);
      blocks_.erase(it);
    }
  }
}

std::string describe(const std::vector<HeapStats>& heaps) {
  auto mib = [](VkDeviceSize bytes) { return static_cast<double>(bytes) / (1 << 20); };
  std::string text;
  for (const HeapStats& h : heaps) {
    if (h.blocks == 0) continue;
    text += fmt::format(
        "{}heap {} ({}, {:.1f} GiB): {:.1f} MiB reserved in {} block(s), {:.1f} MiB used by {} "
        "allocation(s)",
        text.empty() ? "" : "\n", h.heap, h.device_local ? "device-local" : "host",
        mib(h.heap_size) / 1024.0, mib(h.reserved), h.blocks, mib(h.used), h.allocations);
  }
  return text.empty() ? "no device memory allocated" : text;
}

std::vector<HeapStats> MemoryAllocator::stats() const {
  std::lock_guard lock(mutex_);
  std::vector<HeapStats> heaps = dedicated_;
  for (std::uint32_t h = 0; h < properties_.memoryHeapCount; ++h) {
    heaps[h].heap = h;
    heaps[h].heap_size = properties_.memoryHeaps[h].size;
    heaps[h].device_local =
        (properties_.memoryHeaps[h].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT) != 0;
  }
  for (const auto& block : blocks_) {
    HeapStats& s = heaps[properties_.memoryTypes[block->type].heapIndex];
    s.reserved += block->offsets.capacity();
    s.used += block->offsets.used();
    ++s.blocks;
    s.allocations += static_cast<std::uint32_t>(block->offsets.allocation_count());
  }
  return heaps;
}

}  // namespace lantern::runtime
