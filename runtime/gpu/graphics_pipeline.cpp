// Graphics pipeline creation for dynamic rendering, and the rendering scope helpers.
#include "runtime/gpu/graphics_pipeline.h"

#include <fmt/format.h>

#include "engine/core/error.h"
#include "runtime/core/device.h"
#include "runtime/core/vk_check.h"
#include "runtime/gpu/shader_library.h"

namespace lantern::runtime {
namespace {

std::array<const ShaderReflection*, 2> checked_stages(const Device& device,
                                                      const std::shared_ptr<const ShaderCode>& v,
                                                      const std::shared_ptr<const ShaderCode>& f) {
  if (!device.caps().dynamic_rendering)
    throw RuntimeError(
        "GraphicsPipeline needs dynamic rendering (Vulkan 1.3 or VK_KHR_dynamic_rendering)");
  if (!v || !f) throw RuntimeError("GraphicsPipeline: null shader");
  if (v->reflection.stage != VK_SHADER_STAGE_VERTEX_BIT ||
      f->reflection.stage != VK_SHADER_STAGE_FRAGMENT_BIT)
    throw RuntimeError(
        fmt::format("GraphicsPipeline: expected a vertex and a fragment shader, got '{}' and '{}'",
                    v->name, f->name));
  return {&v->reflection, &f->reflection};
}

}  // namespace

GraphicsPipeline::GraphicsPipeline(Device& device, std::shared_ptr<const ShaderCode> vertex,
                                   std::shared_ptr<const ShaderCode> fragment,
                                   const GraphicsPipelineDesc& desc)
    : Pipeline(device, desc.name.empty() && vertex ? vertex->name : desc.name,
               VK_PIPELINE_BIND_POINT_GRAPHICS, checked_stages(device, vertex, fragment)) {
  const ShaderReflection* reflections[] = {&vertex->reflection, &fragment->reflection};
  const auto constants = desc.constants.resolve(reflections, name_);
  std::vector<VkSpecializationMapEntry> entries;
  std::vector<std::uint32_t> data;
  const VkSpecializationInfo spec = make_specialization_info(constants, entries, data);

  VkShaderModule modules[2] = {create_module(*vertex), create_module(*fragment)};
  VkPipelineShaderStageCreateInfo stages[2]{};
  for (int i = 0; i < 2; ++i) {
    stages[i].sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
    stages[i].stage = reflections[i]->stage;
    stages[i].module = modules[i];
    stages[i].pName = reflections[i]->entry_point.c_str();
    stages[i].pSpecializationInfo = constants.empty() ? nullptr : &spec;
  }

  const VkVertexInputBindingDescription vertex_binding{0, desc.vertex_stride,
                                                       VK_VERTEX_INPUT_RATE_VERTEX};
  VkPipelineVertexInputStateCreateInfo vertex_input{
      VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
  if (desc.vertex_stride > 0) {
    vertex_input.vertexBindingDescriptionCount = 1;
    vertex_input.pVertexBindingDescriptions = &vertex_binding;
    vertex_input.vertexAttributeDescriptionCount =
        static_cast<std::uint32_t>(desc.vertex_attributes.size());
    vertex_input.pVertexAttributeDescriptions = desc.vertex_attributes.data();
  }
  VkPipelineInputAssemblyStateCreateInfo assembly{
      VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
  assembly.topology = desc.topology;
  VkPipelineViewportStateCreateInfo viewport{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
  viewport.viewportCount = 1;
  viewport.scissorCount = 1;
  VkPipelineRasterizationStateCreateInfo raster{
      VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
  raster.polygonMode = VK_POLYGON_MODE_FILL;
  raster.cullMode = desc.cull_mode;
  raster.frontFace = desc.front_face;
  raster.lineWidth = 1.0f;
  VkPipelineMultisampleStateCreateInfo multisample{
      VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
  multisample.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
  VkPipelineDepthStencilStateCreateInfo depth{
      VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
  const bool has_depth = desc.depth_format != VK_FORMAT_UNDEFINED;
  depth.depthTestEnable = has_depth && desc.depth_test;
  depth.depthWriteEnable = has_depth && desc.depth_write;
  depth.depthCompareOp = desc.depth_compare;
  std::vector<VkPipelineColorBlendAttachmentState> blend_attachments(desc.color_formats.size());
  for (auto& a : blend_attachments) {
    a.colorWriteMask = 0xf;  // no blending unless asked: G-buffer style writes
    if (desc.alpha_blend) {
      a.blendEnable = VK_TRUE;
      a.srcColorBlendFactor = VK_BLEND_FACTOR_SRC_ALPHA;
      a.dstColorBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
      a.colorBlendOp = VK_BLEND_OP_ADD;
      a.srcAlphaBlendFactor = VK_BLEND_FACTOR_ONE;
      a.dstAlphaBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
      a.alphaBlendOp = VK_BLEND_OP_ADD;
    }
  }
  VkPipelineColorBlendStateCreateInfo blend{
      VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
  blend.attachmentCount = static_cast<std::uint32_t>(blend_attachments.size());
  blend.pAttachments = blend_attachments.data();
  const VkDynamicState dynamic_states[] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
  VkPipelineDynamicStateCreateInfo dynamic{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
  dynamic.dynamicStateCount = 2;
  dynamic.pDynamicStates = dynamic_states;
  VkPipelineRenderingCreateInfoKHR rendering{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO_KHR};
  rendering.colorAttachmentCount = static_cast<std::uint32_t>(desc.color_formats.size());
  rendering.pColorAttachmentFormats = desc.color_formats.data();
  rendering.depthAttachmentFormat = desc.depth_format;

  VkGraphicsPipelineCreateInfo info{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
  info.pNext = &rendering;
  info.stageCount = 2;
  info.pStages = stages;
  info.pVertexInputState = &vertex_input;
  info.pInputAssemblyState = &assembly;
  info.pViewportState = &viewport;
  info.pRasterizationState = &raster;
  info.pMultisampleState = &multisample;
  info.pDepthStencilState = &depth;
  info.pColorBlendState = &blend;
  info.pDynamicState = &dynamic;
  info.layout = layout_;
  const VkResult result = vkCreateGraphicsPipelines(device.handle(), device.pipeline_cache(), 1,
                                                    &info, nullptr, &pipeline_);
  for (VkShaderModule m : modules) vkDestroyShaderModule(device.handle(), m, nullptr);
  VK_CHECK(result);
  device.set_name(pipeline_, name_);
}

void begin_rendering(const Device& device, VkCommandBuffer cmd, VkExtent2D extent,
                     std::span<const ColorTarget> colors, const DepthTarget* depth) {
  std::vector<VkRenderingAttachmentInfoKHR> color_infos;
  for (const ColorTarget& c : colors) {
    VkRenderingAttachmentInfoKHR a{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO_KHR};
    a.imageView = c.view;
    a.imageLayout = c.layout;
    a.loadOp = c.clear ? VK_ATTACHMENT_LOAD_OP_CLEAR : VK_ATTACHMENT_LOAD_OP_LOAD;
    a.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    if (c.clear) a.clearValue.color = *c.clear;
    color_infos.push_back(a);
  }
  VkRenderingAttachmentInfoKHR depth_info{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO_KHR};
  if (depth != nullptr) {
    depth_info.imageView = depth->view;
    depth_info.imageLayout = depth->layout;
    depth_info.loadOp = depth->clear ? VK_ATTACHMENT_LOAD_OP_CLEAR : VK_ATTACHMENT_LOAD_OP_LOAD;
    depth_info.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    if (depth->clear) depth_info.clearValue.depthStencil = {*depth->clear, 0};
  }
  VkRenderingInfoKHR info{VK_STRUCTURE_TYPE_RENDERING_INFO_KHR};
  info.renderArea = {{0, 0}, extent};
  info.layerCount = 1;
  info.colorAttachmentCount = static_cast<std::uint32_t>(color_infos.size());
  info.pColorAttachments = color_infos.data();
  info.pDepthAttachment = depth != nullptr ? &depth_info : nullptr;
  device.fn().cmd_begin_rendering(cmd, &info);
  const VkViewport viewport{
      0.0f, 0.0f, static_cast<float>(extent.width), static_cast<float>(extent.height), 0.0f, 1.0f};
  const VkRect2D scissor{{0, 0}, extent};
  vkCmdSetViewport(cmd, 0, 1, &viewport);
  vkCmdSetScissor(cmd, 0, 1, &scissor);
}

void end_rendering(const Device& device, VkCommandBuffer cmd) {
  device.fn().cmd_end_rendering(cmd);
}

}  // namespace lantern::runtime
