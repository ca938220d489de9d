// Every shader and variant in the build's manifest: the .spv exists, passes spirv-val and
// reflection; default variants also compile through the run-time glslang library with the same
// bindings. Plus: compile errors name the file and line.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "runtime/gpu/glsl_compiler.h"
#include "runtime/gpu/shader_library.h"
#include "runtime/gpu/spirv_reflect.h"
#include "tests/runtime/scratch_dir.h"

namespace lantern::runtime {
namespace {

struct ManifestEntry {
  std::string relpath, variant;
  std::vector<std::string> defines;
};

std::vector<ManifestEntry> read_manifest(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::vector<ManifestEntry> entries;
  for (std::string line; std::getline(in, line);) {
    if (line.empty()) continue;
    std::stringstream fields(line);
    ManifestEntry e;
    std::string defines;
    std::getline(fields, e.relpath, '|');
    std::getline(fields, e.variant, '|');
    std::getline(fields, defines);
    std::stringstream list(defines);  // a CMake list: NAME=VALUE;NAME2
    for (std::string d; std::getline(list, d, ';');)
      if (!d.empty()) e.defines.push_back(d);
    entries.push_back(e);
  }
  return entries;
}

bool spirv_val_passes(const std::filesystem::path& spv) {
  const std::string command = "spirv-val --target-env vulkan1.2 '" + spv.string() + "'";
  return std::system(command.c_str()) == 0;
}

TEST(ShaderCompile, EveryManifestShaderIsValidReflectsAndRecompiles) {
  ASSERT_EQ(std::system("command -v spirv-val > /dev/null"), 0)
      << "spirv-val not on PATH (package spirv-tools)";
  ShaderLibrary library;
  const auto entries = read_manifest(library.dir() / "manifest.txt");
  ASSERT_FALSE(entries.empty()) << "empty manifest in " << library.dir();
  int recompiled = 0;
  for (const ManifestEntry& e : entries) {
    SCOPED_TRACE(e.relpath + (e.variant.empty() ? "" : "." + e.variant));
    const auto spv = library.spirv_path(e.relpath, e.variant);
    ASSERT_TRUE(std::filesystem::exists(spv)) << spv;
    EXPECT_TRUE(spirv_val_passes(spv)) << spv;
    std::shared_ptr<const ShaderCode> built;
    ASSERT_NO_THROW(built = library.load(e.relpath, e.variant));
    if (!e.variant.empty()) continue;

    const auto source = std::filesystem::path(LANTERN_SOURCE_DIR) / "shaders" / e.relpath;
    const GlslResult result = compile_glsl(source, {}, e.defines);
    ASSERT_TRUE(result.ok()) << result.log;
    const ShaderReflection runtime = reflect_spirv(result.spirv, source.string());
    ASSERT_EQ(runtime.bindings.size(), built->reflection.bindings.size());
    for (std::size_t i = 0; i < runtime.bindings.size(); ++i) {
      EXPECT_EQ(runtime.bindings[i].name, built->reflection.bindings[i].name);
      EXPECT_EQ(runtime.bindings[i].binding, built->reflection.bindings[i].binding);
      EXPECT_EQ(runtime.bindings[i].type, built->reflection.bindings[i].type);
    }
    EXPECT_EQ(runtime.push_constant_bytes, built->reflection.push_constant_bytes);
    EXPECT_EQ(runtime.local_size, built->reflection.local_size);
    ++recompiled;
  }
  EXPECT_GT(recompiled, 0);
}

TEST(ShaderCompile, ErrorsNameFileAndLine) {
  const auto& dir = lantern::test::process_scratch_dir();
  const auto file = dir / "broken.comp";
  std::ofstream(file)
      << "#version 460\nlayout(local_size_x = 1) in;\nvoid main() {\n  undeclared_thing = 1;\n}\n";
  const GlslResult result = compile_glsl(file);
  EXPECT_FALSE(result.ok());
  EXPECT_NE(result.log.find(file.string() + ":4"), std::string::npos) << result.log;
}

TEST(ShaderCompile, DefinesReachThePreprocessor) {
  const auto& dir = lantern::test::process_scratch_dir();
  const auto file = dir / "needs_define.comp";
  std::ofstream(file) << "#version 460\n#ifndef LANTERN_TEST_SIZE\n#error missing define\n#endif\n"
                         "layout(local_size_x = LANTERN_TEST_SIZE) in;\nvoid main() {}\n";
  EXPECT_FALSE(compile_glsl(file).ok());
  const std::vector<std::string> defines = {"LANTERN_TEST_SIZE=16"};
  const GlslResult result = compile_glsl(file, {}, defines);
  ASSERT_TRUE(result.ok()) << result.log;
  EXPECT_EQ(reflect_spirv(result.spirv, "needs_define").local_size[0], 16u);
}

}  // namespace
}  // namespace lantern::runtime
