// Run-time GLSL -> SPIR-V through the glslang library, with the same settings as the build
// (Vulkan 1.2 / SPIR-V 1.5, #include resolved against shaders/) — for hot reload and tests.
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

namespace lantern::runtime {

struct GlslResult {
  std::vector<std::uint32_t> spirv;  // empty on failure
  std::string log;                   // glslang messages, each "ERROR: <file>:<line>: ..."
  bool ok() const { return !spirv.empty(); }
};

// `stage` 0: derived from the extension (.comp .vert .frag .rgen .rmiss .rchit .rahit).
// `defines`: "NAME" or "NAME=VALUE". `include_dirs` empty: the build's include path (the source
// tree's shaders/ directory, then the NanoVDB headers).
// Never throws for shader errors (they are in the result); throws lantern::InputError when the
// file cannot be read or the stage is unknown.
GlslResult compile_glsl(const std::filesystem::path& path, VkShaderStageFlagBits stage = {},
                        std::span<const std::string> defines = {},
                        std::span<const std::filesystem::path> include_dirs = {});

VkShaderStageFlagBits stage_from_extension(const std::filesystem::path& path);

}  // namespace lantern::runtime
