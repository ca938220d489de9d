// SPIR-V reflection of the build's test shaders: binding names/kinds, push constants, spec
// constants, local size — and malformed input rejected (no device needed).
#include "runtime/gpu/spirv_reflect.h"

#include <gtest/gtest.h>

#include <bit>

#include "engine/core/error.h"
#include "runtime/gpu/shader_library.h"

namespace lantern::runtime {
namespace {

TEST(SpirvReflect, FindsNamedBindingsOfEveryKind) {
  ShaderLibrary library;
  const auto code = library.load("tests/runtime_reflect.comp");
  const ShaderReflection& r = code->reflection;
  EXPECT_EQ(r.stage, VK_SHADER_STAGE_COMPUTE_BIT);
  EXPECT_EQ(r.entry_point, "main");
  ASSERT_EQ(r.bindings.size(), 5u);
  struct Expected {
    const char* name;
    std::uint32_t binding;
    VkDescriptorType type;
  };
  const Expected expected[] = {
      {"frame", 0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER},
      {"source", 1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
      {"Reservoirs", 2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},  // no instance name: the block name
      {"radiance", 3, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE},
      {"history", 4, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
  };
  for (const Expected& e : expected) {
    const DescriptorBinding* b = r.find_binding(e.name);
    ASSERT_NE(b, nullptr) << e.name;
    EXPECT_EQ(b->set, 0u) << e.name;
    EXPECT_EQ(b->binding, e.binding) << e.name;
    EXPECT_EQ(b->type, e.type) << e.name;
    EXPECT_EQ(b->count, 1u) << e.name;
    EXPECT_EQ(b->stages, static_cast<VkShaderStageFlags>(VK_SHADER_STAGE_COMPUTE_BIT));
  }
  EXPECT_EQ(r.find_binding("radiance")->image_format, VK_FORMAT_R32G32B32A32_SFLOAT);
  EXPECT_EQ(r.find_binding("nonexistent"), nullptr);
  EXPECT_EQ(r.push_constant_bytes, 64u + 16u);  // mat4 + uvec4
  EXPECT_EQ(r.local_size, (std::array<std::uint32_t, 3>{8, 4, 1}));
  EXPECT_EQ(r.local_size_spec_id, (std::array<int, 3>{-1, -1, -1}));

  const SpecConstant* use_scale = r.find_spec_constant("kUseScale");
  const SpecConstant* scale = r.find_spec_constant("kScale");
  ASSERT_NE(use_scale, nullptr);
  ASSERT_NE(scale, nullptr);
  EXPECT_EQ(use_scale->id, 3u);
  EXPECT_EQ(use_scale->default_value, 1u);
  EXPECT_EQ(scale->id, 7u);
  EXPECT_EQ(std::bit_cast<float>(scale->default_value), 2.0f);
}

TEST(SpirvReflect, SpecialisedLocalSizeAndPushConstants) {
  ShaderLibrary library;
  const ShaderReflection& r = library.load("tests/runtime_fill.comp")->reflection;
  EXPECT_EQ(r.local_size_spec_id[0], 0);
  EXPECT_EQ(r.local_size_spec_id[1], -1);
  EXPECT_EQ(r.push_constant_bytes, 8u);
  ASSERT_EQ(r.bindings.size(), 1u);
  EXPECT_EQ(r.bindings[0].name, "result");
  ASSERT_NE(r.find_spec_constant("kMultiplier"), nullptr);
  EXPECT_EQ(r.find_spec_constant("kMultiplier")->default_value, 3u);
}

TEST(SpirvReflect, RejectsMalformedModules) {
  const std::vector<std::uint32_t> not_spirv = {1, 2, 3, 4, 5, 6};
  EXPECT_THROW(reflect_spirv(not_spirv, "junk"), RuntimeError);
  ShaderLibrary library;
  auto words = library.load("tests/runtime_fill.comp")->spirv;
  words.resize(words.size() - 3);  // cut the last instruction short
  words.back() = 0xffff0000u | 0x3du;
  EXPECT_THROW(reflect_spirv(words, "truncated"), RuntimeError);
  EXPECT_THROW(library.load("tests/does_not_exist.comp"), RuntimeError);
}

}  // namespace
}  // namespace lantern::runtime
