// A raster pipeline (vertex + fragment) for dynamic rendering (no VkRenderPass): colour and depth
// attachment formats are part of the description; viewport and scissor are dynamic. Plus a small
// begin/end-rendering helper for passes like the G-buffer.
#pragma once

#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "runtime/gpu/pipeline.h"

namespace lantern::runtime {

struct GraphicsPipelineDesc {
  std::string name;  // default: the vertex shader's name
  std::vector<VkFormat> color_formats;
  VkFormat depth_format = VK_FORMAT_UNDEFINED;  // UNDEFINED: no depth attachment
  // One interleaved vertex buffer at binding 0 (stride 0: no vertex input, e.g. full-screen
  // passes).
  std::uint32_t vertex_stride = 0;
  std::vector<VkVertexInputAttributeDescription> vertex_attributes;  // binding must be 0
  VkPrimitiveTopology topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
  VkCullModeFlags cull_mode = VK_CULL_MODE_BACK_BIT;
  VkFrontFace front_face = VK_FRONT_FACE_COUNTER_CLOCKWISE;
  bool depth_test = true;
  bool depth_write = true;
  VkCompareOp depth_compare = VK_COMPARE_OP_LESS_OR_EQUAL;
  // Alpha blending on every colour attachment ("over": colour SRC_ALPHA / ONE_MINUS_SRC_ALPHA,
  // alpha ONE / ONE_MINUS_SRC_ALPHA, so a layer cleared to 0 ends up premultiplied), e.g. UI.
  // false: plain writes (G-buffer style).
  bool alpha_blend = false;
  SpecConstants constants;
};

class GraphicsPipeline : public Pipeline {
 public:
  // Throws lantern::RuntimeError when the device lacks dynamic rendering.
  GraphicsPipeline(Device& device, std::shared_ptr<const ShaderCode> vertex,
                   std::shared_ptr<const ShaderCode> fragment, const GraphicsPipelineDesc& desc);
  GraphicsPipeline(GraphicsPipeline&&) noexcept = default;
  ~GraphicsPipeline() = default;
};

struct ColorTarget {
  VkImageView view = VK_NULL_HANDLE;
  VkImageLayout layout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  std::optional<VkClearColorValue> clear;  // nullopt: load existing contents
};

struct DepthTarget {
  VkImageView view = VK_NULL_HANDLE;
  VkImageLayout layout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
  std::optional<float> clear;
};

// vkCmdBeginRendering over the full `extent`, and sets viewport + scissor to it.
void begin_rendering(const Device& device, VkCommandBuffer cmd, VkExtent2D extent,
                     std::span<const ColorTarget> colors, const DepthTarget* depth = nullptr);
void end_rendering(const Device& device, VkCommandBuffer cmd);

}  // namespace lantern::runtime
