// Access → stages/access/layout mapping and the text forms used by RenderGraph::dump().
#include "runtime/graph/resource_desc.h"

#include <utility>

namespace lantern::runtime::graph {

bool is_write(Access a) {
  switch (a) {
    case Access::StorageWrite:
    case Access::StorageReadWrite:
    case Access::ColorAttachment:
    case Access::DepthAttachment:
    case Access::TransferDst:
    case Access::AccelerationStructureBuild:
    case Access::HostReadWrite:
      return true;
    default:
      return false;
  }
}

bool is_read(Access a) {
  return a == Access::StorageReadWrite || a == Access::HostReadWrite || !is_write(a);
}

bool allowed_on_buffer(Access a) {
  switch (a) {
    case Access::Sampled:
    case Access::ColorAttachment:
    case Access::DepthAttachment:
    case Access::DepthRead:
      return false;
    default:
      return true;
  }
}

bool allowed_on_image(Access a) {
  switch (a) {
    case Access::UniformRead:
    case Access::UniformTexelRead:
    case Access::VertexBuffer:
    case Access::IndexBuffer:
    case Access::IndirectBuffer:
    case Access::AccelerationStructureBuildInput:
    case Access::AccelerationStructureBuild:
    case Access::AccelerationStructureRead:
    case Access::HostReadWrite:
      return false;
    default:
      return true;
  }
}

const char* access_name(Access a) {
  switch (a) {
    case Access::StorageRead:
      return "storage-read";
    case Access::StorageWrite:
      return "storage-write";
    case Access::StorageReadWrite:
      return "storage-read-write";
    case Access::UniformRead:
      return "uniform-read";
    case Access::UniformTexelRead:
      return "uniform-texel-read";
    case Access::Sampled:
      return "sampled";
    case Access::ColorAttachment:
      return "color-attachment";
    case Access::DepthAttachment:
      return "depth-attachment";
    case Access::DepthRead:
      return "depth-read";
    case Access::TransferSrc:
      return "transfer-src";
    case Access::TransferDst:
      return "transfer-dst";
    case Access::VertexBuffer:
      return "vertex-buffer";
    case Access::IndexBuffer:
      return "index-buffer";
    case Access::IndirectBuffer:
      return "indirect-buffer";
    case Access::AccelerationStructureBuildInput:
      return "acceleration-structure-build-input";
    case Access::AccelerationStructureBuild:
      return "acceleration-structure-build";
    case Access::AccelerationStructureRead:
      return "acceleration-structure-read";
    case Access::HostReadWrite:
      return "host-read-write";
  }
  return "?";
}

const char* pass_kind_name(PassKind k) {
  switch (k) {
    case PassKind::Compute:
      return "compute";
    case PassKind::Graphics:
      return "graphics";
    case PassKind::Transfer:
      return "transfer";
    case PassKind::Host:
      return "host";
  }
  return "?";
}

namespace {

VkPipelineStageFlags2 shader_stages(PassKind kind) {
  switch (kind) {
    case PassKind::Compute:
      return VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
    case PassKind::Graphics:
      return VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT;
    case PassKind::Transfer:
    case PassKind::Host:
      return VK_PIPELINE_STAGE_2_NONE;  // rejected by validation
  }
  return VK_PIPELINE_STAGE_2_NONE;
}

}  // namespace

AccessState access_state(Access a, PassKind kind, bool is_image) {
  const VkPipelineStageFlags2 shaders = shader_stages(kind);
  const VkImageLayout storage_layout =
      is_image ? VK_IMAGE_LAYOUT_GENERAL : VK_IMAGE_LAYOUT_UNDEFINED;
  switch (a) {
    case Access::StorageRead:
      return {shaders, VK_ACCESS_2_SHADER_STORAGE_READ_BIT, storage_layout};
    case Access::StorageWrite:
      return {shaders, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, storage_layout};
    case Access::StorageReadWrite:
      return {shaders, VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
              storage_layout};
    case Access::UniformRead:
      return {shaders, VK_ACCESS_2_UNIFORM_READ_BIT, VK_IMAGE_LAYOUT_UNDEFINED};
    case Access::UniformTexelRead:
      // Synchronization2: SHADER_SAMPLED_READ covers uniform texel buffers (UNIFORM_READ is for
      // uniform buffers only).
      return {shaders, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT, VK_IMAGE_LAYOUT_UNDEFINED};
    case Access::Sampled:
      return {shaders, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT,
              VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    case Access::ColorAttachment:
      return {VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
              VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT,
              VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    case Access::DepthAttachment:
      return {VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT |
                  VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
              VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT |
                  VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
              VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL};
    case Access::DepthRead:
      return {VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT |
                  VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
              VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT,
              VK_IMAGE_LAYOUT_DEPTH_READ_ONLY_OPTIMAL};
    case Access::TransferSrc:
      return {VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT,
              is_image ? VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL : VK_IMAGE_LAYOUT_UNDEFINED};
    case Access::TransferDst:
      return {VK_PIPELINE_STAGE_2_COPY_BIT | VK_PIPELINE_STAGE_2_CLEAR_BIT,
              VK_ACCESS_2_TRANSFER_WRITE_BIT,
              is_image ? VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL : VK_IMAGE_LAYOUT_UNDEFINED};
    case Access::VertexBuffer:
      return {VK_PIPELINE_STAGE_2_VERTEX_ATTRIBUTE_INPUT_BIT, VK_ACCESS_2_VERTEX_ATTRIBUTE_READ_BIT,
              VK_IMAGE_LAYOUT_UNDEFINED};
    case Access::IndexBuffer:
      return {VK_PIPELINE_STAGE_2_INDEX_INPUT_BIT, VK_ACCESS_2_INDEX_READ_BIT,
              VK_IMAGE_LAYOUT_UNDEFINED};
    case Access::IndirectBuffer:
      return {VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT, VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT,
              VK_IMAGE_LAYOUT_UNDEFINED};
    // Build inputs are read with SHADER_READ in the build stage (Vulkan spec, "Acceleration
    // Structure" synchronisation); a build reads and writes its destination and scratch.
    case Access::AccelerationStructureBuildInput:
      return {VK_PIPELINE_STAGE_2_ACCELERATION_STRUCTURE_BUILD_BIT_KHR, VK_ACCESS_2_SHADER_READ_BIT,
              VK_IMAGE_LAYOUT_UNDEFINED};
    case Access::AccelerationStructureBuild:
      return {VK_PIPELINE_STAGE_2_ACCELERATION_STRUCTURE_BUILD_BIT_KHR,
              VK_ACCESS_2_ACCELERATION_STRUCTURE_READ_BIT_KHR |
                  VK_ACCESS_2_ACCELERATION_STRUCTURE_WRITE_BIT_KHR,
              VK_IMAGE_LAYOUT_UNDEFINED};
    case Access::AccelerationStructureRead:
      return {shaders, VK_ACCESS_2_ACCELERATION_STRUCTURE_READ_BIT_KHR, VK_IMAGE_LAYOUT_UNDEFINED};
    case Access::HostReadWrite:
      return {VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT | VK_ACCESS_2_HOST_WRITE_BIT,
              VK_IMAGE_LAYOUT_UNDEFINED};
  }
  return {};
}

VkBufferUsageFlags buffer_usage(Access a) {
  switch (a) {
    case Access::StorageRead:
    case Access::StorageWrite:
    case Access::StorageReadWrite:
      return VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    case Access::UniformRead:
      return VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT;
    case Access::UniformTexelRead:
      return VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT;
    case Access::TransferSrc:
      return VK_BUFFER_USAGE_TRANSFER_SRC_BIT;
    case Access::TransferDst:
      return VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    case Access::VertexBuffer:
      return VK_BUFFER_USAGE_VERTEX_BUFFER_BIT;
    case Access::IndexBuffer:
      return VK_BUFFER_USAGE_INDEX_BUFFER_BIT;
    case Access::IndirectBuffer:
      return VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT;
    case Access::AccelerationStructureBuildInput:
      return VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_BUILD_INPUT_READ_ONLY_BIT_KHR;
    case Access::AccelerationStructureBuild:
    case Access::AccelerationStructureRead:
      return VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_STORAGE_BIT_KHR;
    default:
      return 0;
  }
}

VkImageUsageFlags image_usage(Access a) {
  switch (a) {
    case Access::StorageRead:
    case Access::StorageWrite:
    case Access::StorageReadWrite:
      return VK_IMAGE_USAGE_STORAGE_BIT;
    case Access::Sampled:
      return VK_IMAGE_USAGE_SAMPLED_BIT;
    case Access::ColorAttachment:
      return VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;
    case Access::DepthAttachment:
    case Access::DepthRead:
      return VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT;
    case Access::TransferSrc:
      return VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    case Access::TransferDst:
      return VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    default:
      return 0;
  }
}

namespace {

template <class Flags, size_t N>
std::string join_flags(Flags flags, const std::pair<Flags, const char*> (&names)[N]) {
  if (flags == 0) return "NONE";
  std::string out;
  for (const auto& [bit, name] : names) {
    if ((flags & bit) == 0) continue;
    if (!out.empty()) out += '|';
    out += name;
    flags &= ~bit;
  }
  if (flags != 0) out += out.empty() ? "OTHER" : "|OTHER";
  return out;
}

}  // namespace

std::string stage_names(VkPipelineStageFlags2 stages) {
  static const std::pair<VkPipelineStageFlags2, const char*> kNames[] = {
      {VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT, "DRAW_INDIRECT"},
      {VK_PIPELINE_STAGE_2_INDEX_INPUT_BIT, "INDEX_INPUT"},
      {VK_PIPELINE_STAGE_2_VERTEX_ATTRIBUTE_INPUT_BIT, "VERTEX_ATTRIBUTE_INPUT"},
      {VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT, "VERTEX_SHADER"},
      {VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT, "FRAGMENT_SHADER"},
      {VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT, "EARLY_FRAGMENT_TESTS"},
      {VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT, "LATE_FRAGMENT_TESTS"},
      {VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, "COLOR_ATTACHMENT_OUTPUT"},
      {VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, "COMPUTE_SHADER"},
      {VK_PIPELINE_STAGE_2_COPY_BIT, "COPY"},
      {VK_PIPELINE_STAGE_2_CLEAR_BIT, "CLEAR"},
      {VK_PIPELINE_STAGE_2_HOST_BIT, "HOST"},
      {VK_PIPELINE_STAGE_2_ACCELERATION_STRUCTURE_BUILD_BIT_KHR, "ACCELERATION_STRUCTURE_BUILD"},
      {VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, "ALL_COMMANDS"},
      {VK_PIPELINE_STAGE_2_BOTTOM_OF_PIPE_BIT, "BOTTOM_OF_PIPE"},
  };
  return join_flags(stages, kNames);
}

std::string access_names(VkAccessFlags2 access) {
  static const std::pair<VkAccessFlags2, const char*> kNames[] = {
      {VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT, "INDIRECT_COMMAND_READ"},
      {VK_ACCESS_2_INDEX_READ_BIT, "INDEX_READ"},
      {VK_ACCESS_2_VERTEX_ATTRIBUTE_READ_BIT, "VERTEX_ATTRIBUTE_READ"},
      {VK_ACCESS_2_UNIFORM_READ_BIT, "UNIFORM_READ"},
      {VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT, "COLOR_ATTACHMENT_READ"},
      {VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, "COLOR_ATTACHMENT_WRITE"},
      {VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT, "DEPTH_STENCIL_READ"},
      {VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT, "DEPTH_STENCIL_WRITE"},
      {VK_ACCESS_2_TRANSFER_READ_BIT, "TRANSFER_READ"},
      {VK_ACCESS_2_TRANSFER_WRITE_BIT, "TRANSFER_WRITE"},
      {VK_ACCESS_2_HOST_READ_BIT, "HOST_READ"},
      {VK_ACCESS_2_HOST_WRITE_BIT, "HOST_WRITE"},
      {VK_ACCESS_2_MEMORY_READ_BIT, "MEMORY_READ"},
      {VK_ACCESS_2_MEMORY_WRITE_BIT, "MEMORY_WRITE"},
      {VK_ACCESS_2_SHADER_SAMPLED_READ_BIT, "SHADER_SAMPLED_READ"},
      {VK_ACCESS_2_SHADER_STORAGE_READ_BIT, "SHADER_STORAGE_READ"},
      {VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, "SHADER_STORAGE_WRITE"},
      {VK_ACCESS_2_SHADER_READ_BIT, "SHADER_READ"},
      {VK_ACCESS_2_ACCELERATION_STRUCTURE_READ_BIT_KHR, "ACCELERATION_STRUCTURE_READ"},
      {VK_ACCESS_2_ACCELERATION_STRUCTURE_WRITE_BIT_KHR, "ACCELERATION_STRUCTURE_WRITE"},
  };
  return join_flags(access, kNames);
}

const char* layout_name(VkImageLayout layout) {
  switch (layout) {
    case VK_IMAGE_LAYOUT_UNDEFINED:
      return "UNDEFINED";
    case VK_IMAGE_LAYOUT_GENERAL:
      return "GENERAL";
    case VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL:
      return "COLOR_ATTACHMENT";
    case VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL:
      return "DEPTH_ATTACHMENT";
    case VK_IMAGE_LAYOUT_DEPTH_READ_ONLY_OPTIMAL:
      return "DEPTH_READ_ONLY";
    case VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL:
      return "SHADER_READ_ONLY";
    case VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL:
      return "TRANSFER_SRC";
    case VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL:
      return "TRANSFER_DST";
    case VK_IMAGE_LAYOUT_PRESENT_SRC_KHR:
      return "PRESENT_SRC";
    default:
      return "OTHER";
  }
}

}  // namespace lantern::runtime::graph
