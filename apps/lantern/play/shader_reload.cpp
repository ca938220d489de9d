// ShaderReloader (shader_reload.h).
#include "apps/lantern/play/shader_reload.h"

#include <fmt/format.h>

#include <chrono>
#include <cstdlib>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>

#include "engine/core/log.h"
#include "runtime/gpu/glsl_compiler.h"
#include "runtime/gpu/shader_library.h"

namespace lantern::app {
namespace {

namespace fs = std::filesystem;

double now_s() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

bool is_shader_source(const fs::path& p) {
  static const std::set<std::string> kExt = {".comp", ".vert",  ".frag",  ".glsl", ".h",
                                             ".rgen", ".rmiss", ".rchit", ".rahit"};
  return kExt.count(p.extension().string()) != 0;
}

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::string cur;
  std::istringstream in(s);
  while (std::getline(in, cur, sep))
    if (!cur.empty()) out.push_back(cur);
  return out;
}

}  // namespace

fs::path ShaderReloader::default_source_dir() {
  if (const char* env = std::getenv("LANTERN_SHADER_SOURCE_DIR"); env != nullptr && *env != '\0')
    return env;
#ifdef LANTERN_PLAY_SHADER_SOURCE_DIR
  return LANTERN_PLAY_SHADER_SOURCE_DIR;
#else
  return "shaders";
#endif
}

ShaderReloader::ShaderReloader(fs::path source_dir, fs::path spirv_dir)
    : source_dir_(std::move(source_dir)), spirv_dir_(std::move(spirv_dir)) {
  std::ifstream manifest(spirv_dir_ / "manifest.txt");
  if (!manifest) {
    log::warn("shader reload: no {} (hot reload disabled)", (spirv_dir_ / "manifest.txt").string());
    return;
  }
  for (std::string line; std::getline(manifest, line);) {
    const auto fields = line.find('|');
    if (fields == std::string::npos) continue;
    const auto second = line.find('|', fields + 1);
    Entry e;
    e.rel = line.substr(0, fields);
    e.variant = line.substr(fields + 1,
                            second == std::string::npos ? std::string::npos : second - fields - 1);
    if (second != std::string::npos) e.defines = split(line.substr(second + 1), ';');
    entries_.push_back(std::move(e));
  }
}

std::vector<std::string> ShaderReloader::poll(double interval_s) {
  const double t = now_s();
  if (interval_s > 0.0 && t - last_poll_ < interval_s) return {};
  last_poll_ = t;
  std::vector<std::string> changed;
  std::error_code ec;
  if (!fs::is_directory(source_dir_, ec)) return {};
  for (auto it = fs::recursive_directory_iterator(source_dir_, ec);
       !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
    if (!it->is_regular_file(ec) || !is_shader_source(it->path())) continue;
    const auto mtime = it->last_write_time(ec);
    if (ec) continue;
    const std::string rel = fs::relative(it->path(), source_dir_, ec).generic_string();
    auto [slot, inserted] = mtimes_.try_emplace(rel, mtime);
    if (!inserted && slot->second != mtime) {
      slot->second = mtime;
      changed.push_back(rel);
    } else if (inserted && primed_) {
      changed.push_back(rel);
    }
  }
  primed_ = true;
  return changed;
}

std::vector<std::string> ShaderReloader::dependencies(const std::string& rel) const {
  // The file and its #include closure; includes resolve against the including file's folder,
  // then the source root (as glslangValidator -I<shaders> does).
  static const std::regex kInclude(R"re(^\s*#\s*include\s*"([^"]+)")re");
  std::set<std::string> seen;
  std::vector<std::string> todo{rel};
  while (!todo.empty()) {
    const std::string file = todo.back();
    todo.pop_back();
    if (!seen.insert(file).second) continue;
    std::ifstream in(source_dir_ / file);
    for (std::string line; std::getline(in, line);) {
      std::smatch m;
      if (!std::regex_search(line, m, kInclude)) continue;
      const fs::path local = (fs::path(file).parent_path() / m[1].str()).lexically_normal();
      todo.push_back(fs::exists(source_dir_ / local) ? local.generic_string()
                                                     : fs::path(m[1].str()).generic_string());
    }
  }
  return {seen.begin(), seen.end()};
}

ReloadResult ShaderReloader::recompile(const std::vector<std::string>& changed) {
  ReloadResult result;
  result.changed = changed;
  const std::set<std::string> changed_set(changed.begin(), changed.end());
  std::vector<
      std::pair<std::pair<std::string, std::string>, std::shared_ptr<const runtime::ShaderCode>>>
      fresh;
  for (const Entry& e : entries_) {
    const auto deps = dependencies(e.rel);
    const bool affected = std::any_of(
        deps.begin(), deps.end(), [&](const std::string& d) { return changed_set.count(d) != 0; });
    if (!affected) continue;
    const std::string name = e.variant.empty() ? e.rel : e.rel + "." + e.variant;
    const std::vector<fs::path> include_dirs{source_dir_};
    runtime::GlslResult r;
    try {
      r = runtime::compile_glsl(source_dir_ / e.rel, {}, e.defines, include_dirs);
    } catch (const std::exception& error) {
      r.log = error.what();
    }
    if (!r.ok()) {
      result.errors += fmt::format("{}:\n{}\n", name, r.log.empty() ? "compile failed" : r.log);
      continue;
    }
    try {
      fresh.push_back({{e.rel, e.variant}, runtime::make_shader_code(name, std::move(r.spirv))});
      result.compiled.push_back(name);
    } catch (const std::exception& error) {
      result.errors += fmt::format("{}: {}\n", name, error.what());
    }
  }
  if (result.ok())
    for (auto& [key, code] : fresh) overrides_[key] = std::move(code);
  return result;
}

std::unique_ptr<runtime::ShaderLibrary> ShaderReloader::make_library() const {
  auto library = std::make_unique<runtime::ShaderLibrary>(spirv_dir_);
  for (const auto& [key, code] : overrides_) library->replace(key.first, key.second, code);
  return library;
}

}  // namespace lantern::app
