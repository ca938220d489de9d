// Pipeline: what compute and graphics pipelines share — a descriptor set layout derived from the
// shaders' reflection (set 0, push descriptors), the push-constant range, specialisation constants
// by name, and binding resources BY NAME through Bindings.
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "runtime/gpu/spirv_reflect.h"

namespace lantern::runtime {

class Device;
class Bindings;
struct ShaderCode;

// Specialisation constants by the name the shader gives them (or by constant_id).
class SpecConstants {
 public:
  SpecConstants& set(std::string name, std::uint32_t value);
  SpecConstants& set(std::string name, std::int32_t value);
  SpecConstants& set(std::string name, float value);
  SpecConstants& set(std::string name, bool value);
  SpecConstants& set_id(std::uint32_t constant_id, std::uint32_t value);

  // Resolves names against the shaders; throws lantern::RuntimeError for unknown names.
  // Returns (constant_id, 32-bit value) pairs.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> resolve(
      std::span<const ShaderReflection* const> shaders, std::string_view pipeline) const;

 private:
  struct Entry {
    std::string name;  // empty: by id
    std::uint32_t id = 0;
    std::uint32_t bits = 0;
  };
  std::vector<Entry> entries_;
};

class Pipeline {
 public:
  Pipeline(const Pipeline&) = delete;
  Pipeline& operator=(const Pipeline&) = delete;

  VkPipeline handle() const { return pipeline_; }
  VkPipelineLayout layout() const { return layout_; }
  VkPipelineBindPoint bind_point() const { return bind_point_; }
  const std::string& name() const { return name_; }
  // The descriptors the shaders statically use (the layout; see spirv_reflect.h).
  std::span<const DescriptorBinding> bindings() const { return bindings_; }
  const DescriptorBinding* find_binding(std::string_view name) const;
  // Whether `name` is declared by a stage but used by none (Bindings accepts and ignores it).
  bool declares_unused(std::string_view name) const;
  std::uint32_t push_constant_bytes() const { return push_constant_bytes_; }
  Device& device() const { return *device_; }

  // Binds the pipeline and pushes its descriptors (every reflected binding must be set).
  void bind(VkCommandBuffer cmd, const Bindings& bindings) const;
  // Binds a pipeline that has no descriptors.
  void bind(VkCommandBuffer cmd) const;
  // Push constants; `bytes` must equal the shader's push-constant block size.
  void push_constants(VkCommandBuffer cmd, const void* data, std::uint32_t bytes) const;
  template <class T>
  void push_constants(VkCommandBuffer cmd, const T& value) const {
    push_constants(cmd, &value, static_cast<std::uint32_t>(sizeof(T)));
  }

 protected:
  Pipeline(Device& device, std::string name, VkPipelineBindPoint bind_point,
           std::span<const ShaderReflection* const> stages);
  Pipeline(Pipeline&& other) noexcept;
  ~Pipeline();
  // Shader module for pipeline creation; destroyed by the caller right after.
  VkShaderModule create_module(const ShaderCode& code) const;

  Device* device_ = nullptr;
  std::string name_;
  VkPipelineBindPoint bind_point_ = VK_PIPELINE_BIND_POINT_COMPUTE;
  std::vector<DescriptorBinding> bindings_;
  std::vector<std::string> unused_names_;
  std::uint32_t push_constant_bytes_ = 0;
  VkShaderStageFlags push_constant_stages_ = 0;
  VkDescriptorSetLayout set_layout_ = VK_NULL_HANDLE;
  VkPipelineLayout layout_ = VK_NULL_HANDLE;
  VkPipeline pipeline_ = VK_NULL_HANDLE;
};

// Packs resolved constants into a VkSpecializationInfo; the info points into `data` and `entries`.
VkSpecializationInfo make_specialization_info(
    const std::vector<std::pair<std::uint32_t, std::uint32_t>>& constants,
    std::vector<VkSpecializationMapEntry>& entries, std::vector<std::uint32_t>& data);

}  // namespace lantern::runtime
