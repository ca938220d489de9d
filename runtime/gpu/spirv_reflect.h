// A small SPIR-V reflection: reads the binary words (no external library) and derives what a
// pipeline needs from the shader itself — descriptor bindings with their names (those the entry
// point statically uses: loads, stores, access chains, atomics, calls), push-constant size,
// specialisation constants and the compute local size — so callers bind by name; and the layout
// of every named struct (member names, Offset and ArrayStride decorations), which tests/layout
// compares with the C++ side of each shared struct. The project's one SPIR-V reader.
#pragma once

#include <vulkan/vulkan.h>

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace lantern::runtime {

struct DescriptorBinding {
  std::string name;  // the GLSL instance name, else the block/type name
  std::uint32_t set = 0;
  std::uint32_t binding = 0;
  VkDescriptorType type = VK_DESCRIPTOR_TYPE_MAX_ENUM;
  std::uint32_t count = 1;  // array size; 0 = runtime-sized array (bindless)
  VkShaderStageFlags stages = 0;
  VkFormat image_format = VK_FORMAT_UNDEFINED;  // storage images: the declared format, if any
};

struct SpecConstant {
  std::string name;  // e.g. "kCandidates" for `layout(constant_id = 0) const uint kCandidates = 8;`
  std::uint32_t id = 0;
  std::uint32_t default_value = 0;  // raw 32 bits (bools are 0/1)
};

// A named struct type as the module lays it out.
struct StructLayout {
  std::string name;
  std::vector<std::string> member_names;     // by member index ("" when unnamed)
  std::vector<std::int64_t> member_offsets;  // by member index (-1 when undecorated)
  std::int64_t array_stride = -1;            // stride of an array of this struct (-1: none)
};

struct ShaderReflection {
  VkShaderStageFlagBits stage = VK_SHADER_STAGE_COMPUTE_BIT;
  std::string entry_point = "main";
  // Descriptors the entry point statically uses, sorted by (set, binding): the pipeline layout.
  std::vector<DescriptorBinding> bindings;
  // Declared but never used by the entry point (e.g. a shared include's buffers a pass does not
  // read): left out of the layout, so a pass binds and declares only what its code reads.
  std::vector<DescriptorBinding> unused_bindings;
  std::vector<SpecConstant> spec_constants;
  std::uint32_t push_constant_bytes = 0;
  std::array<std::uint32_t, 3> local_size{1, 1, 1};   // compute only; defaults if specialised
  std::array<int, 3> local_size_spec_id{-1, -1, -1};  // spec id that overrides each axis, or -1
  // Every named struct type, by name; where glslang emits one name for several struct ids (a
  // block and a plain copy), the copy with Offset decorations.
  std::vector<StructLayout> structs;

  const DescriptorBinding* find_binding(std::string_view name) const;
  const SpecConstant* find_spec_constant(std::string_view name) const;
  const StructLayout* find_struct(std::string_view name) const;
};

// Parses a SPIR-V module. `what` names it in error messages. Throws lantern::RuntimeError on
// malformed input (bad magic, truncated instruction, unsupported descriptor type).
ShaderReflection reflect_spirv(std::span<const std::uint32_t> words, std::string_view what);

// Merges the bindings of several stages (same set/binding must agree on type and count).
std::vector<DescriptorBinding> merge_bindings(std::span<const ShaderReflection* const> stages,
                                              std::string_view what);

const char* descriptor_type_name(VkDescriptorType type);

}  // namespace lantern::runtime
