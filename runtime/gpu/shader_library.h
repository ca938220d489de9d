// Loads compiled SPIR-V by its source-relative path ("restir/restir_initial.comp" ->
// <dir>/restir/restir_initial.comp.spv; variant "rq" -> ...comp.rq.spv), reflects it once and
// caches it. The directory is, in order: the constructor argument, $LANTERN_SHADER_DIR, the
// build's shader dir (compile definition LANTERN_SHADER_DIR), <exe dir>/../shaders. A program
// built against the installed package passes its config's Lantern_SHADER_DIR (README "Embedding").
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

#include "runtime/gpu/spirv_reflect.h"

namespace lantern::runtime {

struct ShaderCode {
  std::string name;  // relpath[.variant], for messages and debug names
  std::vector<std::uint32_t> spirv;
  ShaderReflection reflection;
};

class ShaderLibrary {
 public:
  explicit ShaderLibrary(std::filesystem::path dir = {});

  // Throws lantern::RuntimeError naming the file when it is missing or not valid SPIR-V.
  std::shared_ptr<const ShaderCode> load(std::string_view relpath, std::string_view variant = "");
  // Hot reload: from now on load(relpath, variant) returns `code` (e.g. compile_glsl output
  // wrapped by make_shader_code); pipelines built earlier keep the code they were built with.
  void replace(std::string_view relpath, std::string_view variant,
               std::shared_ptr<const ShaderCode> code);
  const std::filesystem::path& dir() const { return dir_; }
  std::filesystem::path spirv_path(std::string_view relpath, std::string_view variant = "") const;

  static std::filesystem::path default_dir();

 private:
  std::filesystem::path dir_;
  std::mutex mutex_;
  std::map<std::string, std::shared_ptr<const ShaderCode>, std::less<>> cache_;
};

// Wraps SPIR-V produced elsewhere (e.g. compile_glsl for hot reload) with its reflection.
std::shared_ptr<const ShaderCode> make_shader_code(std::string name,
                                                   std::vector<std::uint32_t> spirv);

// Reads a .spv file into words; throws lantern::RuntimeError if missing or of odd size.
std::vector<std::uint32_t> read_spirv_file(const std::filesystem::path& path);

}  // namespace lantern::runtime
