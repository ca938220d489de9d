// JSON levels: the document, glTF assets, camera, environment, settings and generators.
// Sections are read in dependency order (materials and behaviours before what uses them).
#include "engine/level/json_level.h"

#include <fmt/format.h>

#include <algorithm>
#include <fstream>
#include <sstream>

#include "engine/core/error.h"
#include "engine/level/generators/generator.h"
#include "engine/level/gltf_importer.h"
#include "engine/level/json_level_reader.h"

namespace lantern {
namespace {
constexpr long kMaxSettingsDepth = 32;
}  // namespace

void read_json_level(const std::filesystem::path& file, Level& level,
                     LoadDiagnostics& diagnostics) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(fmt::format("{}: cannot open level file", file.string()));
  std::stringstream text;
  text << in.rdbuf();
  const nlohmann::json document = parse_json_text(text.str(), file);
  JsonLevelReader reader(file, level, diagnostics);
  reader.read(document);
}

void JsonLevelReader::read(const nlohmann::json& document) {
  JsonObject root(document, "", file_);
  if (root.has("description")) root.string("description");
  if (root.has("materials")) {
    JsonObject section = root.object("materials");
    read_materials(section);
  }
  if (root.has("paths")) {
    JsonObject section = root.object("paths");
    read_paths(section);
  }
  if (root.has("behaviours")) {
    JsonObject section = root.object("behaviours");
    read_behaviours(section);
  }
  if (root.has("assets")) read_assets(root.raw("assets"), root.pointer("assets"));
  if (root.has("primitives")) {
    const std::string ptr = root.pointer("primitives");
    const nlohmann::json& list = expect_array(root.raw("primitives"), ptr, file_);
    for (std::size_t i = 0; i < list.size(); ++i) {
      JsonObject p(list[i], fmt::format("{}/{}", ptr, i), file_);
      read_primitive(p);
    }
  }
  if (root.has("lights")) {
    const std::string ptr = root.pointer("lights");
    const nlohmann::json& list = expect_array(root.raw("lights"), ptr, file_);
    for (std::size_t i = 0; i < list.size(); ++i) {
      JsonObject l(list[i], fmt::format("{}/{}", ptr, i), file_);
      read_light(l);
    }
  }
  if (root.has("generators")) read_generators(root.raw("generators"), root.pointer("generators"));
  if (root.has("volumes")) {
    const std::string ptr = root.pointer("volumes");
    const nlohmann::json& list = expect_array(root.raw("volumes"), ptr, file_);
    for (std::size_t i = 0; i < list.size(); ++i) {
      JsonObject v(list[i], fmt::format("{}/{}", ptr, i), file_);
      read_volume(v);
    }
  }
  if (root.has("environment")) {
    JsonObject env = root.object("environment");
    read_environment(env);
  }
  if (root.has("settings")) {
    if (!root.raw("settings").is_object())
      root.fail("settings", "expected an object of key: value");
    read_settings(root.raw("settings"), "", root.pointer("settings"));
  }
  if (root.has("budgets")) level().budgets = existing_file(root, "budgets");
  if (root.has("camera")) {
    JsonObject cam = root.object("camera");
    read_camera(cam);
  } else if (asset_camera_) {
    level().camera = *asset_camera_;
    level().has_camera = true;
  }
  root.finish();
  check_follow_paths();
}

std::filesystem::path JsonLevelReader::existing_file(JsonObject& owner, std::string_view key) {
  const std::string name = owner.string(key);
  const std::filesystem::path path = std::filesystem::absolute(file_.parent_path() / name);
  if (!std::filesystem::is_regular_file(path))
    owner.fail(key, fmt::format("file '{}' not found (looked for {})", name, path.string()));
  return path;
}

void JsonLevelReader::read_assets(const nlohmann::json& section, const std::string& pointer) {
  const nlohmann::json& list = expect_array(section, pointer, file_);
  for (std::size_t i = 0; i < list.size(); ++i) {
    JsonObject a(list[i], fmt::format("{}/{}", pointer, i), file_);
    const std::filesystem::path path = existing_file(a, "file");
    const Transform placement = read_transform(a);
    std::optional<Behaviour> behaviour = behaviour_ref(a);
    a.finish();
    GltfImport imported = import_gltf(path, placement.matrix(), level(), builder_.diagnostics());
    if (behaviour) {
      for (std::size_t k = imported.first_instance; k < level().instances.size(); ++k)
        level().instances[k].behaviour = behaviour;
      for (std::size_t k = imported.first_light; k < level().lights.size(); ++k)
        level().lights[k].behaviour = behaviour;
    }
    if (imported.camera && !asset_camera_) asset_camera_ = imported.camera;
    if (imported.camera_path && !level().find_path(imported.camera_path->name)) {
      if (level().camera_path.empty()) level().camera_path = imported.camera_path->name;
      level().paths.push_back(std::move(*imported.camera_path));
    }
  }
}

void JsonLevelReader::read_camera(JsonObject& c) {
  Camera cam;
  cam.position = c.vec3("position");
  if (c.has("target") && c.has("rotation")) c.fail("give either 'target' or 'rotation', not both");
  if (c.has("target")) {
    const glm::vec3 target = c.vec3("target");
    if (glm::length(target - cam.position) < 1e-6f)
      c.fail("target", "target equals the camera position");
    cam.orientation = look_at_orientation(cam.position, target);
  } else {
    cam.orientation = c.quat("rotation", cam.orientation);
  }
  cam.yfov = glm::radians(c.number("yfov_deg", glm::degrees(cam.yfov)));
  if (!(cam.yfov > 0.0f && cam.yfov < glm::pi<float>())) c.fail("yfov_deg", "must be in (0, 180)");
  cam.aspect = c.number("aspect", 0.0f);
  if (cam.aspect < 0.0f) c.fail("aspect", "must be > 0 (or 0: from the output size)");
  cam.znear = c.number("znear", cam.znear);
  cam.zfar = c.number("zfar", cam.zfar);
  if (!(cam.znear > 0.0f) || (cam.zfar != 0.0f && cam.zfar <= cam.znear))
    c.fail("need 0 < znear < zfar (zfar 0 = infinite)");
  if (c.has("path")) {
    const std::string path = c.string("path");
    if (!level().find_path(path))
      c.fail("path", fmt::format("no path named '{}' in 'paths'", path));
    level().camera_path = path;
  }
  c.finish();
  level().camera = cam;
  level().has_camera = true;
}

void JsonLevelReader::read_environment(JsonObject& e) {
  EnvironmentMap env;
  env.path = existing_file(e, "file");
  env.intensity = e.number("intensity", 1.0f);
  if (env.intensity < 0.0f) e.fail("intensity", "must be >= 0");
  const glm::vec3 euler = glm::radians(e.vec3("rotation_deg", glm::vec3(0.0f)));
  env.rotation = glm::quat(euler);
  e.finish();
  level().environment = env;
}

void JsonLevelReader::read_settings(const nlohmann::json& value, const std::string& prefix,
                                    const std::string& pointer) {
  for (auto it = value.begin(); it != value.end(); ++it) {
    const std::string key = prefix.empty() ? it.key() : prefix + "." + it.key();
    const std::string ptr = pointer + "/" + pointer_token(it.key());
    const nlohmann::json& v = it.value();
    if (v.is_object()) {
      // Recursion depth = nesting in the file: bounded, so a deeply nested document cannot
      // overflow the stack. JSON pointer tokens escape '/', so '/' counts the levels.
      if (std::count(ptr.begin(), ptr.end(), '/') > kMaxSettingsDepth)
        throw InputError(fmt::format("{}: {}: settings nest deeper than {} levels", file_.string(),
                                     ptr, kMaxSettingsDepth));
      read_settings(v, key, ptr);
    } else if (v.is_string()) {
      level().settings[key] = v.get<std::string>();
    } else if (v.is_boolean() || v.is_number()) {
      level().settings[key] = v.dump();
    } else {
      throw InputError(
          fmt::format("{}: {}: setting '{}' must be a string, number or boolean, got {}",
                      file_.string(), ptr, key, v.type_name()));
    }
  }
}

void JsonLevelReader::read_generators(const nlohmann::json& section, const std::string& pointer) {
  const nlohmann::json& list = expect_array(section, pointer, file_);
  for (std::size_t i = 0; i < list.size(); ++i) {
    JsonObject g(list[i], fmt::format("{}/{}", pointer, i), file_);
    run_generator(g, *this);
    g.finish();
  }
}

void JsonLevelReader::check_follow_paths() {
  auto check = [&](const std::optional<Behaviour>& b, const std::string& what) {
    if (!b) return;
    if (const auto* f = std::get_if<FollowPathBehaviour>(&*b); f && !level().find_path(f->path))
      throw InputError(fmt::format("{}: {}: follow_path names path '{}', which is not in 'paths'",
                                   file_.string(), what, f->path));
  };
  for (const Instance& inst : level().instances)
    check(inst.behaviour, fmt::format("instance '{}'", inst.name));
  for (const Light& l : level().lights) check(l.behaviour, fmt::format("light '{}'", l.name));
  for (const Volume& v : level().volumes) check(v.behaviour, fmt::format("volume '{}'", v.name));
}

}  // namespace lantern
