// Compute pipeline creation and dispatch.
#include "runtime/gpu/compute_pipeline.h"

#include <fmt/format.h>

#include "engine/core/error.h"
#include "runtime/core/device.h"
#include "runtime/core/vk_check.h"
#include "runtime/gpu/shader_library.h"

namespace lantern::runtime {
namespace {
const ShaderReflection* checked_compute(const std::shared_ptr<const ShaderCode>& shader) {
  if (!shader) throw RuntimeError("ComputePipeline: null shader");
  if (shader->reflection.stage != VK_SHADER_STAGE_COMPUTE_BIT)
    throw RuntimeError(
        fmt::format("ComputePipeline: shader '{}' is not a compute shader", shader->name));
  return &shader->reflection;
}
}  // namespace

ComputePipeline::ComputePipeline(Device& device, std::shared_ptr<const ShaderCode> shader,
                                 const ComputePipelineDesc& desc)
    : Pipeline(device, desc.name.empty() && shader ? shader->name : desc.name,
               VK_PIPELINE_BIND_POINT_COMPUTE,
               std::span<const ShaderReflection* const>(std::array{checked_compute(shader)})),
      shader_(std::move(shader)) {
  const ShaderReflection& r = shader_->reflection;
  const ShaderReflection* stages[] = {&r};
  const auto constants = desc.constants.resolve(stages, name_);
  local_size_ = r.local_size;
  for (std::size_t axis = 0; axis < 3; ++axis) {
    if (r.local_size_spec_id[axis] < 0) continue;
    for (const auto& [id, bits] : constants)
      if (id == static_cast<std::uint32_t>(r.local_size_spec_id[axis])) local_size_[axis] = bits;
  }
  std::vector<VkSpecializationMapEntry> entries;
  std::vector<std::uint32_t> data;
  const VkSpecializationInfo spec = make_specialization_info(constants, entries, data);

  VkShaderModule module = create_module(*shader_);
  VkComputePipelineCreateInfo info{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
  info.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
  info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
  info.stage.module = module;
  info.stage.pName = r.entry_point.c_str();
  info.stage.pSpecializationInfo = constants.empty() ? nullptr : &spec;
  info.layout = layout_;
  const VkResult result = vkCreateComputePipelines(device.handle(), device.pipeline_cache(), 1,
                                                   &info, nullptr, &pipeline_);
  vkDestroyShaderModule(device.handle(), module, nullptr);
  VK_CHECK(result);
  device.set_name(pipeline_, name_);
}

void ComputePipeline::dispatch(VkCommandBuffer cmd, std::uint32_t x, std::uint32_t y,
                               std::uint32_t z) const {
  vkCmdDispatch(cmd, x, y, z);
}

void ComputePipeline::dispatch_threads(VkCommandBuffer cmd, std::uint32_t x, std::uint32_t y,
                                       std::uint32_t z) const {
  auto groups = [](std::uint32_t n, std::uint32_t size) { return (n + size - 1) / size; };
  vkCmdDispatch(cmd, groups(x, local_size_[0]), groups(y, local_size_[1]),
                groups(z, local_size_[2]));
}

void ComputePipeline::warm_up() const {
  const ComputePipeline* self[] = {this};
  runtime::warm_up(*device_, self);
}

}  // namespace lantern::runtime
