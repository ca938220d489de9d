// Shader hot reload for `lantern play`: polls the mtimes of the GLSL sources under the shader
// source directory (once a second by default), finds the compiled shaders (the build's
// <spirv dir>/manifest.txt: "relpath|variant|DEFINES") whose source or #include closure changed,
// and recompiles them at run time with runtime::compile_glsl. Successful compiles become
// overrides that a fresh ShaderLibrary gets (ShaderLibrary::replace); the caller then builds new
// pipelines from it and keeps the old ones if that fails. Compile errors are returned, not thrown.
//
// Source directory: $LANTERN_SHADER_SOURCE_DIR, else the source tree's shaders/.
#pragma once

#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace lantern::runtime {
class ShaderLibrary;
struct ShaderCode;
}  // namespace lantern::runtime

namespace lantern::app {

struct ReloadResult {
  std::vector<std::string> changed;   // source files (relative) that changed
  std::vector<std::string> compiled;  // shaders recompiled ("rel" or "rel.variant")
  std::string errors;                 // compile errors (empty: all compiled)
  bool ok() const { return errors.empty(); }
};

class ShaderReloader {
 public:
  ShaderReloader(std::filesystem::path source_dir, std::filesystem::path spirv_dir);
  static std::filesystem::path default_source_dir();

  // Source files changed since the last call (the first call only records mtimes). Polls at most
  // every `interval_s` seconds (0: every call).
  std::vector<std::string> poll(double interval_s);
  // Recompiles every shader depending on `changed`; on success adds them to the overrides.
  ReloadResult recompile(const std::vector<std::string>& changed);
  // A ShaderLibrary over the build's SPIR-V with every override so far.
  std::unique_ptr<runtime::ShaderLibrary> make_library() const;

  const std::filesystem::path& source_dir() const { return source_dir_; }
  std::size_t overrides() const { return overrides_.size(); }

 private:
  struct Entry {
    std::string rel;
    std::string variant;
    std::vector<std::string> defines;
  };
  std::vector<std::string> dependencies(const std::string& rel) const;

  std::filesystem::path source_dir_;
  std::filesystem::path spirv_dir_;
  std::vector<Entry> entries_;
  std::map<std::string, std::filesystem::file_time_type> mtimes_;
  bool primed_ = false;
  double last_poll_ = -1e9;
  std::map<std::pair<std::string, std::string>, std::shared_ptr<const runtime::ShaderCode>>
      overrides_;
};

}  // namespace lantern::app
