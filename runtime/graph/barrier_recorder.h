// Records a compiled BarrierBatch into a command buffer: one vkCmdPipelineBarrier2 per batch when
// the device has synchronization2, else one vkCmdPipelineBarrier with the scopes mapped to v1.
#pragma once

#include <vulkan/vulkan.h>

#include <span>

#include "runtime/graph/compiled_graph.h"
#include "runtime/graph/graph_decl.h"
#include "runtime/graph/pass_context.h"

namespace lantern::runtime::graph {

// `barrier2` null selects the Vulkan 1.0 path.
void record_barriers(VkCommandBuffer cmd, PFN_vkCmdPipelineBarrier2KHR barrier2,
                     const BarrierBatch& batch, const GraphDecl& decl,
                     std::span<const PhysicalResource> physical);

// synchronization2 → v1 mappings (exposed for tests).
[[nodiscard]] VkPipelineStageFlags to_stage1(VkPipelineStageFlags2 stages, bool is_src);
[[nodiscard]] VkAccessFlags to_access1(VkAccessFlags2 access);

}  // namespace lantern::runtime::graph
