// SPIR-V loading and the shader directory search order.
#include "runtime/gpu/shader_library.h"

#include <fmt/format.h>

#include <cstdlib>
#include <cstring>
#include <fstream>

#include "engine/core/error.h"

namespace lantern::runtime {

std::vector<std::uint32_t> read_spirv_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) throw RuntimeError(fmt::format("cannot open SPIR-V file {}", path.string()));
  const auto bytes = static_cast<std::size_t>(in.tellg());
  if (bytes == 0 || bytes % 4 != 0)
    throw RuntimeError(fmt::format("{}: {} bytes is not a SPIR-V module", path.string(), bytes));
  std::vector<std::uint32_t> words(bytes / 4);
  in.seekg(0);
  in.read(reinterpret_cast<char*>(words.data()), static_cast<std::streamsize>(bytes));
  if (!in) throw RuntimeError(fmt::format("cannot read SPIR-V file {}", path.string()));
  return words;
}

std::shared_ptr<const ShaderCode> make_shader_code(std::string name,
                                                   std::vector<std::uint32_t> spirv) {
  auto code = std::make_shared<ShaderCode>();
  code->reflection = reflect_spirv(spirv, name);
  code->name = std::move(name);
  code->spirv = std::move(spirv);
  return code;
}

std::filesystem::path ShaderLibrary::default_dir() {
  if (const char* env = std::getenv("LANTERN_SHADER_DIR"); env != nullptr && *env != '\0')
    return env;
#ifdef LANTERN_SHADER_DIR
  if (std::filesystem::is_directory(LANTERN_SHADER_DIR)) return LANTERN_SHADER_DIR;
#endif
  std::error_code ec;
  const auto exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) return exe.parent_path().parent_path() / "shaders";
  return "shaders";
}

ShaderLibrary::ShaderLibrary(std::filesystem::path dir)
    : dir_(dir.empty() ? default_dir() : std::move(dir)) {}

std::filesystem::path ShaderLibrary::spirv_path(std::string_view relpath,
                                                std::string_view variant) const {
  std::string file(relpath);
  if (!variant.empty()) file += fmt::format(".{}", variant);
  return dir_ / (file + ".spv");
}

std::shared_ptr<const ShaderCode> ShaderLibrary::load(std::string_view relpath,
                                                      std::string_view variant) {
  const std::string name =
      variant.empty() ? std::string(relpath) : fmt::format("{}.{}", relpath, variant);
  std::lock_guard lock(mutex_);
  if (auto it = cache_.find(name); it != cache_.end()) return it->second;
  const auto path = spirv_path(relpath, variant);
  if (!std::filesystem::exists(path))
    throw RuntimeError(
        fmt::format("shader '{}' not found: {} does not exist (shader dir {}; set "
                    "LANTERN_SHADER_DIR or rebuild the lantern_shaders target)",
                    name, path.string(), dir_.string()));
  auto code = make_shader_code(name, read_spirv_file(path));
  cache_.emplace(name, code);
  return code;
}

void ShaderLibrary::replace(std::string_view relpath, std::string_view variant,
                            std::shared_ptr<const ShaderCode> code) {
  if (!code) throw RuntimeError(fmt::format("shader '{}': replaced by no code", relpath));
  const std::string name =
      variant.empty() ? std::string(relpath) : fmt::format("{}.{}", relpath, variant);
  std::lock_guard lock(mutex_);
  cache_.insert_or_assign(name, std::move(code));
}

}  // namespace lantern::runtime
