// Shared pipeline machinery: reflected layouts, push descriptors, push constants, spec constants.
#include "runtime/gpu/pipeline.h"

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <utility>

#include "engine/core/error.h"
#include "runtime/core/device.h"
#include "runtime/core/vk_check.h"
#include "runtime/gpu/bindings.h"
#include "runtime/gpu/shader_library.h"

namespace lantern::runtime {

SpecConstants& SpecConstants::set(std::string name, std::uint32_t value) {
  entries_.push_back({std::move(name), 0, value});
  return *this;
}
SpecConstants& SpecConstants::set(std::string name, std::int32_t value) {
  return set(std::move(name), std::bit_cast<std::uint32_t>(value));
}
SpecConstants& SpecConstants::set(std::string name, float value) {
  return set(std::move(name), std::bit_cast<std::uint32_t>(value));
}
SpecConstants& SpecConstants::set(std::string name, bool value) {
  return set(std::move(name), static_cast<std::uint32_t>(value ? 1 : 0));
}
SpecConstants& SpecConstants::set_id(std::uint32_t constant_id, std::uint32_t value) {
  entries_.push_back({{}, constant_id, value});
  return *this;
}

std::vector<std::pair<std::uint32_t, std::uint32_t>> SpecConstants::resolve(
    std::span<const ShaderReflection* const> shaders, std::string_view pipeline) const {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> out;
  for (const Entry& e : entries_) {
    std::uint32_t id = e.id;
    if (!e.name.empty()) {
      const SpecConstant* found = nullptr;
      for (const ShaderReflection* s : shaders)
        if (!found) found = s->find_spec_constant(e.name);
      if (found == nullptr) {
        std::string known;
        for (const ShaderReflection* s : shaders)
          for (const auto& c : s->spec_constants)
            known += fmt::format("{}{} (id {})", known.empty() ? "" : ", ", c.name, c.id);
        throw RuntimeError(
            fmt::format("pipeline '{}': no specialisation constant named '{}' (shader has: {})",
                        pipeline, e.name, known.empty() ? "none" : known));
      }
      id = found->id;
    }
    auto same = std::find_if(out.begin(), out.end(), [&](const auto& p) { return p.first == id; });
    if (same != out.end())
      same->second = e.bits;  // last set wins
    else
      out.emplace_back(id, e.bits);
  }
  return out;
}

VkSpecializationInfo make_specialization_info(
    const std::vector<std::pair<std::uint32_t, std::uint32_t>>& constants,
    std::vector<VkSpecializationMapEntry>& entries, std::vector<std::uint32_t>& data) {
  entries.clear();
  data.clear();
  for (const auto& [id, bits] : constants) {
    entries.push_back({id, static_cast<std::uint32_t>(data.size() * 4), 4});
    data.push_back(bits);
  }
  VkSpecializationInfo info{};
  info.mapEntryCount = static_cast<std::uint32_t>(entries.size());
  info.pMapEntries = entries.data();
  info.dataSize = data.size() * 4;
  info.pData = data.data();
  return info;
}

Pipeline::Pipeline(Device& device, std::string name, VkPipelineBindPoint bind_point,
                   std::span<const ShaderReflection* const> stages)
    : device_(&device),
      name_(std::move(name)),
      bind_point_(bind_point),
      bindings_(merge_bindings(stages, name_)) {
  for (const ShaderReflection* s : stages) {
    for (const DescriptorBinding& b : s->unused_bindings) {
      if (find_binding(b.name) == nullptr) unused_names_.push_back(b.name);
    }
  }
  for (const ShaderReflection* s : stages) {
    if (s->push_constant_bytes > 0)
      push_constant_stages_ |= static_cast<VkShaderStageFlags>(s->stage);
    push_constant_bytes_ = std::max(push_constant_bytes_, s->push_constant_bytes);
  }
  if (push_constant_bytes_ > device.caps().max_push_constant_bytes)
    throw RuntimeError(
        fmt::format("pipeline '{}': {} bytes of push constants exceed the device limit of {}",
                    name_, push_constant_bytes_, device.caps().max_push_constant_bytes));
  if (bindings_.size() > device.caps().max_push_descriptors)
    throw RuntimeError(fmt::format("pipeline '{}': {} bindings exceed maxPushDescriptors {}", name_,
                                   bindings_.size(), device.caps().max_push_descriptors));

  std::vector<VkDescriptorSetLayoutBinding> layout_bindings;
  for (const auto& b : bindings_) {
    // Push descriptors cover set 0 with fixed-size bindings; bindless sets will come with
    // descriptor indexing (caps().descriptor_indexing) as a separate, persistent set.
    if (b.set != 0 || b.count != 1)
      throw RuntimeError(fmt::format(
          "pipeline '{}': binding '{}' (set {}, binding {}, count {}) is not supported: "
          "only single descriptors in set 0 (push descriptors)",
          name_, b.name, b.set, b.binding, b.count));
    layout_bindings.push_back({b.binding, b.type, b.count, b.stages, nullptr});
  }
  VkDescriptorSetLayoutCreateInfo set_info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  set_info.flags = VK_DESCRIPTOR_SET_LAYOUT_CREATE_PUSH_DESCRIPTOR_BIT_KHR;
  set_info.bindingCount = static_cast<std::uint32_t>(layout_bindings.size());
  set_info.pBindings = layout_bindings.data();
  VK_CHECK(vkCreateDescriptorSetLayout(device.handle(), &set_info, nullptr, &set_layout_));

  const VkPushConstantRange range{push_constant_stages_, 0, push_constant_bytes_};
  VkPipelineLayoutCreateInfo layout_info{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  layout_info.setLayoutCount = 1;
  layout_info.pSetLayouts = &set_layout_;
  layout_info.pushConstantRangeCount = push_constant_bytes_ > 0 ? 1 : 0;
  layout_info.pPushConstantRanges = &range;
  VK_CHECK(vkCreatePipelineLayout(device.handle(), &layout_info, nullptr, &layout_));
  device.set_name(set_layout_, name_);
  device.set_name(layout_, name_);
}

Pipeline::Pipeline(Pipeline&& o) noexcept
    : device_(std::exchange(o.device_, nullptr)),
      name_(std::move(o.name_)),
      bind_point_(o.bind_point_),
      bindings_(std::move(o.bindings_)),
      unused_names_(std::move(o.unused_names_)),
      push_constant_bytes_(o.push_constant_bytes_),
      push_constant_stages_(o.push_constant_stages_),
      set_layout_(std::exchange(o.set_layout_, VK_NULL_HANDLE)),
      layout_(std::exchange(o.layout_, VK_NULL_HANDLE)),
      pipeline_(std::exchange(o.pipeline_, VK_NULL_HANDLE)) {}

Pipeline::~Pipeline() {
  if (device_ == nullptr) return;
  vkDestroyPipeline(device_->handle(), pipeline_, nullptr);
  vkDestroyPipelineLayout(device_->handle(), layout_, nullptr);
  vkDestroyDescriptorSetLayout(device_->handle(), set_layout_, nullptr);
}

VkShaderModule Pipeline::create_module(const ShaderCode& code) const {
  VkShaderModuleCreateInfo info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
  info.codeSize = code.spirv.size() * sizeof(std::uint32_t);
  info.pCode = code.spirv.data();
  VkShaderModule module = VK_NULL_HANDLE;
  VK_CHECK(vkCreateShaderModule(device_->handle(), &info, nullptr, &module));
  return module;
}

bool Pipeline::declares_unused(std::string_view name) const {
  return std::find(unused_names_.begin(), unused_names_.end(), name) != unused_names_.end();
}

const DescriptorBinding* Pipeline::find_binding(std::string_view name) const {
  for (const auto& b : bindings_)
    if (b.name == name) return &b;
  return nullptr;
}

void Pipeline::bind(VkCommandBuffer cmd, const Bindings& bindings) const {
  if (&bindings.pipeline() != this)
    throw RuntimeError(fmt::format("pipeline '{}': bound with Bindings made for pipeline '{}'",
                                   name_, bindings.pipeline().name()));
  vkCmdBindPipeline(cmd, bind_point_, pipeline_);
  if (bindings_.empty()) return;
  const auto writes = bindings.writes();
  device_->fn().cmd_push_descriptor_set(cmd, bind_point_, layout_, 0,
                                        static_cast<std::uint32_t>(writes.size()), writes.data());
}

void Pipeline::bind(VkCommandBuffer cmd) const {
  if (!bindings_.empty())
    throw RuntimeError(
        fmt::format("pipeline '{}' has {} descriptor bindings: bind it with Bindings", name_,
                    bindings_.size()));
  vkCmdBindPipeline(cmd, bind_point_, pipeline_);
}

void Pipeline::push_constants(VkCommandBuffer cmd, const void* data, std::uint32_t bytes) const {
  if (bytes != push_constant_bytes_)
    throw RuntimeError(
        fmt::format("pipeline '{}': push constants of {} bytes, the shader declares {}", name_,
                    bytes, push_constant_bytes_));
  vkCmdPushConstants(cmd, layout_, push_constant_stages_, 0, bytes, data);
}

}  // namespace lantern::runtime
