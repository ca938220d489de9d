// Level loading entry point: path resolution, format dispatch, default camera, one warning.
#include "engine/level/level_loader.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstdlib>

#include "engine/core/error.h"
#include "engine/core/log.h"
#include "engine/level/gltf_importer.h"
#include "engine/level/json_level.h"

#ifndef LANTERN_CONTENT_DIR
#error "LANTERN_CONTENT_DIR must be defined by the build (engine/CMakeLists.txt)"
#endif

namespace lantern {
namespace {

bool has_level_extension(const std::filesystem::path& p) {
  const std::string ext = p.extension().string();
  return ext == ".json" || ext == ".gltf" || ext == ".glb";
}

// A camera that sees the whole level from the front and a little above.
Camera framing_camera(const Level& level) {
  Aabb box;
  for (const Instance& inst : level.instances)
    box.grow(level.meshes[inst.mesh].bounds.transformed(inst.world));
  Camera cam;
  if (box.empty()) {
    cam.position = glm::vec3(0.0f, 1.0f, 5.0f);
    cam.orientation = look_at_orientation(cam.position, glm::vec3(0.0f));
    return cam;
  }
  const float radius = std::max(0.5f * glm::length(box.extent()), 1e-3f);
  const float distance = radius / std::tan(0.5f * cam.yfov) * 1.1f;
  cam.position = box.centroid() + glm::normalize(glm::vec3(0.0f, 0.35f, 1.0f)) * distance;
  cam.orientation = look_at_orientation(cam.position, box.centroid());
  cam.znear = std::max(distance * 1e-3f, 1e-3f);
  return cam;
}

}  // namespace

std::filesystem::path content_dir() {
  if (const char* env = std::getenv("LANTERN_CONTENT_DIR"); env && *env) return env;
  return LANTERN_CONTENT_DIR;
}

std::filesystem::path resolve_level_path(std::string_view argument) {
  const std::filesystem::path p(argument);
  if (argument.empty()) throw InputError("no level given");
  if (has_level_extension(p)) {
    if (!std::filesystem::is_regular_file(p))
      throw InputError(fmt::format("{}: level file not found", p.string()));
    return p;
  }
  if (p.has_extension())
    throw InputError(fmt::format("{}: not a level (expected .json, .gltf or .glb, or a level name)",
                                 p.string()));
  const std::filesystem::path levels = content_dir() / "levels";
  const std::filesystem::path named = levels / (std::string(argument) + ".json");
  if (std::filesystem::is_regular_file(named)) return named;
  std::vector<std::string> names;
  if (std::filesystem::is_directory(levels))
    for (const auto& e : std::filesystem::directory_iterator(levels))
      if (e.path().extension() == ".json") names.push_back(e.path().stem().string());
  std::sort(names.begin(), names.end());
  std::string known;
  for (const auto& n : names) known += (known.empty() ? "" : ", ") + n;
  throw InputError(
      fmt::format("level '{}' not found: not a file, and not a level in {} (levels: {})", argument,
                  levels.string(), known.empty() ? "none" : known));
}

Level load_level(const std::filesystem::path& file) {
  if (!std::filesystem::is_regular_file(file))
    throw InputError(fmt::format("{}: level file not found", file.string()));
  Level level;
  level.name = file.stem().string();
  level.source = file;
  LoadDiagnostics diagnostics;
  const std::string ext = file.extension().string();
  if (ext == ".json") {
    read_json_level(file, level, diagnostics);
  } else if (ext == ".gltf" || ext == ".glb") {
    GltfImport imported = import_gltf(file, glm::mat4(1.0f), level, diagnostics);
    if (imported.camera) {
      level.camera = *imported.camera;
      level.has_camera = true;
    }
    if (imported.camera_path) {
      level.camera_path = imported.camera_path->name;
      level.paths.push_back(std::move(*imported.camera_path));
    }
  } else {
    throw InputError(fmt::format("{}: not a level (expected .json, .gltf or .glb)", file.string()));
  }
  if (!level.has_camera) {
    level.camera = framing_camera(level);
    log::info("{}: no camera in the level; framing the scene", file.string());
  }
  if (diagnostics.degenerate_triangles > 0)
    log::warn("{}: skipped {} degenerate (zero-area) triangle{}", file.string(),
              diagnostics.degenerate_triangles, diagnostics.degenerate_triangles == 1 ? "" : "s");
  return level;
}

}  // namespace lantern
