// Staging uploads and readbacks.
#include "runtime/gpu/transfer.h"

#include <fmt/format.h>

#include "engine/core/error.h"
#include "runtime/core/device.h"

namespace lantern::runtime {

void transition_image(Device& device, VkCommandBuffer cmd, const Image& image, VkImageLayout from,
                      VkImageLayout to) {
  VkImageMemoryBarrier2 barrier{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
  barrier.srcStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
  barrier.srcAccessMask = VK_ACCESS_2_MEMORY_WRITE_BIT;
  barrier.dstStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
  barrier.dstAccessMask = VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT;
  barrier.oldLayout = from;
  barrier.newLayout = to;
  barrier.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  barrier.image = image.handle();
  barrier.subresourceRange = {image.aspect(), 0, 1, 0, 1};
  VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  dependency.imageMemoryBarrierCount = 1;
  dependency.pImageMemoryBarriers = &barrier;
  device.fn().cmd_pipeline_barrier2(cmd, &dependency);
}

void upload_buffer(Device& device, Buffer& dst, std::span<const std::byte> data,
                   VkDeviceSize offset) {
  if (offset + data.size() > dst.size())
    throw RuntimeError(
        fmt::format("upload of {} bytes at offset {} overflows buffer '{}' ({} bytes)", data.size(),
                    offset, dst.name(), dst.size()));
  if (data.empty()) return;
  if (dst.mapped() != nullptr) {  // host-visible and coherent: write directly
    std::memcpy(dst.mapped() + offset, data.data(), data.size());
    return;
  }
  Buffer staging(device, {.size = data.size(),
                          .usage = VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                          .memory = MemoryUsage::Upload,
                          .name = dst.name() + ".staging"});
  std::memcpy(staging.mapped(), data.data(), data.size());
  device.submit_and_wait([&](VkCommandBuffer cmd) {
    const VkBufferCopy region{0, offset, data.size()};
    vkCmdCopyBuffer(cmd, staging.handle(), dst.handle(), 1, &region);
  });
}

std::vector<std::byte> read_buffer_bytes(Device& device, const Buffer& src) {
  std::vector<std::byte> out(src.size());
  if (src.mapped() != nullptr) {
    std::memcpy(out.data(), src.mapped(), out.size());
    return out;
  }
  Buffer staging(device, {.size = src.size(),
                          .usage = VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                          .memory = MemoryUsage::Readback,
                          .name = src.name() + ".readback"});
  device.submit_and_wait([&](VkCommandBuffer cmd) {
    const VkBufferCopy region{0, 0, src.size()};
    vkCmdCopyBuffer(cmd, src.handle(), staging.handle(), 1, &region);
  });
  std::memcpy(out.data(), staging.mapped(), out.size());
  return out;
}

void upload_image(Device& device, Image& dst, std::span<const std::byte> texels,
                  VkImageLayout final_layout) {
  const VkExtent2D e = dst.extent();
  const VkDeviceSize bytes = VkDeviceSize{e.width} * e.height * texel_size(dst.format());
  if (texels.size() != bytes)
    throw RuntimeError(fmt::format("upload to image '{}' ({}x{}) needs {} bytes, got {}",
                                   dst.name(), e.width, e.height, bytes, texels.size()));
  Buffer staging(device, {.size = bytes,
                          .usage = VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                          .memory = MemoryUsage::Upload,
                          .name = dst.name() + ".staging"});
  std::memcpy(staging.mapped(), texels.data(), texels.size());
  device.submit_and_wait([&](VkCommandBuffer cmd) {
    transition_image(device, cmd, dst, VK_IMAGE_LAYOUT_UNDEFINED,
                     VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
    VkBufferImageCopy region{};
    region.imageSubresource = {dst.aspect(), 0, 0, 1};
    region.imageExtent = {e.width, e.height, 1};
    vkCmdCopyBufferToImage(cmd, staging.handle(), dst.handle(),
                           VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
    transition_image(device, cmd, dst, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, final_layout);
  });
}

std::vector<std::byte> read_image(Device& device, const Image& src, VkImageLayout layout) {
  const VkExtent2D e = src.extent();
  const VkDeviceSize bytes = VkDeviceSize{e.width} * e.height * texel_size(src.format());
  Buffer staging(device, {.size = bytes,
                          .usage = VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                          .memory = MemoryUsage::Readback,
                          .name = src.name() + ".readback"});
  device.submit_and_wait([&](VkCommandBuffer cmd) {
    transition_image(device, cmd, src, layout, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
    VkBufferImageCopy region{};
    region.imageSubresource = {src.aspect(), 0, 0, 1};
    region.imageExtent = {e.width, e.height, 1};
    vkCmdCopyImageToBuffer(cmd, src.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                           staging.handle(), 1, &region);
    if (layout != VK_IMAGE_LAYOUT_UNDEFINED)
      transition_image(device, cmd, src, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, layout);
  });
  std::vector<std::byte> out(bytes);
  std::memcpy(out.data(), staging.mapped(), out.size());
  return out;
}

}  // namespace lantern::runtime
