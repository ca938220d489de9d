// Create-infos of transient buffers, images and their views.
#include "runtime/graph/transient_create_info.h"

#include "runtime/gpu/image.h"

namespace lantern::runtime::graph {

VkBufferCreateInfo transient_buffer_info(const ResourceDecl& r) {
  VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  info.size = r.buffer.size;
  // Transfer usage always: clears and debug readback of any transient stay possible.
  info.usage = r.buffer_usage | VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  return info;
}

VkImageCreateInfo transient_image_info(const ResourceDecl& r) {
  VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  info.imageType = r.image.extent.depth > 1 ? VK_IMAGE_TYPE_3D : VK_IMAGE_TYPE_2D;
  info.format = r.image.format;
  info.extent = r.image.extent;
  info.mipLevels = r.image.mip_levels;
  info.arrayLayers = r.image.array_layers;
  info.samples = VK_SAMPLE_COUNT_1_BIT;
  info.tiling = VK_IMAGE_TILING_OPTIMAL;
  info.usage = r.image_usage | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  return info;
}

VkImageViewCreateInfo transient_view_info(const ResourceDecl& r, VkImage image) {
  VkImageViewCreateInfo view{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
  view.image = image;
  view.viewType = r.image.extent.depth > 1   ? VK_IMAGE_VIEW_TYPE_3D
                  : r.image.array_layers > 1 ? VK_IMAGE_VIEW_TYPE_2D_ARRAY
                                             : VK_IMAGE_VIEW_TYPE_2D;
  view.format = r.image.format;
  view.subresourceRange = {aspect_of(r.image.format), 0, r.image.mip_levels, 0,
                           r.image.array_layers};
  return view;
}

}  // namespace lantern::runtime::graph
