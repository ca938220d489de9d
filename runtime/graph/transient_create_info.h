// Vulkan create-infos for graph-owned transients, shared by the memory-requirement query at
// compile time and the real creation at record time so both see identical objects.
#pragma once

#include <vulkan/vulkan.h>

#include "runtime/graph/graph_decl.h"

namespace lantern::runtime::graph {

[[nodiscard]] VkBufferCreateInfo transient_buffer_info(const ResourceDecl& resource);
[[nodiscard]] VkImageCreateInfo transient_image_info(const ResourceDecl& resource);
[[nodiscard]] VkImageViewCreateInfo transient_view_info(const ResourceDecl& resource,
                                                        VkImage image);

}  // namespace lantern::runtime::graph
