// BarrierBatch → Vulkan barrier commands (synchronization2, or v1 as a fallback).
#include "runtime/graph/barrier_recorder.h"

#include <vector>

#include "runtime/gpu/image.h"

namespace lantern::runtime::graph {

namespace {

VkImageSubresourceRange whole_image(const ImageDesc& desc) {
  return {aspect_of(desc.format), 0, VK_REMAINING_MIP_LEVELS, 0, VK_REMAINING_ARRAY_LAYERS};
}

}  // namespace

VkPipelineStageFlags to_stage1(VkPipelineStageFlags2 stages, bool is_src) {
  constexpr VkPipelineStageFlags2 kTransfer =
      VK_PIPELINE_STAGE_2_COPY_BIT | VK_PIPELINE_STAGE_2_BLIT_BIT |
      VK_PIPELINE_STAGE_2_RESOLVE_BIT | VK_PIPELINE_STAGE_2_CLEAR_BIT;
  VkPipelineStageFlags out = static_cast<VkPipelineStageFlags>(stages & 0xFFFFFFFFull & ~kTransfer);
  if ((stages & kTransfer) != 0) out |= VK_PIPELINE_STAGE_TRANSFER_BIT;
  if (out == 0)
    out = is_src ? VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT : VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT;
  return out;
}

VkAccessFlags to_access1(VkAccessFlags2 access) {
  VkAccessFlags out = static_cast<VkAccessFlags>(access & 0xFFFFFFFFull);
  if ((access & (VK_ACCESS_2_SHADER_SAMPLED_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_READ_BIT)) != 0)
    out |= VK_ACCESS_SHADER_READ_BIT;
  if ((access & VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT) != 0) out |= VK_ACCESS_SHADER_WRITE_BIT;
  return out;
}

void record_barriers(VkCommandBuffer cmd, PFN_vkCmdPipelineBarrier2KHR barrier2,
                     const BarrierBatch& batch, const GraphDecl& decl,
                     std::span<const PhysicalResource> physical) {
  if (batch.empty()) return;
  std::vector<VkMemoryBarrier2> memory;
  std::vector<VkBufferMemoryBarrier2> buffers;
  std::vector<VkImageMemoryBarrier2> images;
  for (const ResourceBarrier& b : batch.barriers) {
    const ResourceDecl& r = decl.resources[b.resource];
    if (b.aliasing)  // the bytes were another resource's: order against it as memory
      memory.push_back({VK_STRUCTURE_TYPE_MEMORY_BARRIER_2, nullptr, b.src.stages, b.src.access,
                        b.dst.stages, b.dst.access});
    if (r.is_image) {
      VkImageMemoryBarrier2 ib{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
      ib.srcStageMask = b.src.stages;
      ib.srcAccessMask = b.src.access;
      ib.dstStageMask = b.dst.stages;
      ib.dstAccessMask = b.dst.access;
      ib.oldLayout = b.src.layout;
      ib.newLayout = b.dst.layout;
      ib.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
      ib.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
      ib.image = physical[b.resource].image;
      ib.subresourceRange = whole_image(r.image);
      images.push_back(ib);
    } else {
      VkBufferMemoryBarrier2 bb{VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER_2};
      bb.srcStageMask = b.src.stages;
      bb.srcAccessMask = b.src.access;
      bb.dstStageMask = b.dst.stages;
      bb.dstAccessMask = b.dst.access;
      bb.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
      bb.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
      bb.buffer = physical[b.resource].buffer;
      bb.offset = 0;
      bb.size = VK_WHOLE_SIZE;
      buffers.push_back(bb);
    }
  }

  if (barrier2 != nullptr) {
    VkDependencyInfo info{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
    info.memoryBarrierCount = static_cast<uint32_t>(memory.size());
    info.pMemoryBarriers = memory.data();
    info.bufferMemoryBarrierCount = static_cast<uint32_t>(buffers.size());
    info.pBufferMemoryBarriers = buffers.data();
    info.imageMemoryBarrierCount = static_cast<uint32_t>(images.size());
    info.pImageMemoryBarriers = images.data();
    barrier2(cmd, &info);
    return;
  }

  // Vulkan 1.0: one stage mask pair for the whole batch (the union: conservative, correct).
  VkPipelineStageFlags2 src = 0, dst = 0;
  std::vector<VkMemoryBarrier> memory1;
  std::vector<VkBufferMemoryBarrier> buffers1;
  std::vector<VkImageMemoryBarrier> images1;
  for (const VkMemoryBarrier2& m : memory) {
    src |= m.srcStageMask;
    dst |= m.dstStageMask;
    memory1.push_back({VK_STRUCTURE_TYPE_MEMORY_BARRIER, nullptr, to_access1(m.srcAccessMask),
                       to_access1(m.dstAccessMask)});
  }
  for (const VkBufferMemoryBarrier2& b : buffers) {
    src |= b.srcStageMask;
    dst |= b.dstStageMask;
    buffers1.push_back({VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER, nullptr,
                        to_access1(b.srcAccessMask), to_access1(b.dstAccessMask),
                        VK_QUEUE_FAMILY_IGNORED, VK_QUEUE_FAMILY_IGNORED, b.buffer, b.offset,
                        b.size});
  }
  for (const VkImageMemoryBarrier2& i : images) {
    src |= i.srcStageMask;
    dst |= i.dstStageMask;
    images1.push_back({VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER, nullptr, to_access1(i.srcAccessMask),
                       to_access1(i.dstAccessMask), i.oldLayout, i.newLayout,
                       VK_QUEUE_FAMILY_IGNORED, VK_QUEUE_FAMILY_IGNORED, i.image,
                       i.subresourceRange});
  }
  vkCmdPipelineBarrier(cmd, to_stage1(src, true), to_stage1(dst, false), 0,
                       static_cast<uint32_t>(memory1.size()), memory1.data(),
                       static_cast<uint32_t>(buffers1.size()), buffers1.data(),
                       static_cast<uint32_t>(images1.size()), images1.data());
}

}  // namespace lantern::runtime::graph
