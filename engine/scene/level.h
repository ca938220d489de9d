// A loaded level as plain data, independent of the ECS: a later step instantiates it into the
// world. Units follow CLI.md "glTF units" (metres, radiometric, factor 1).
#pragma once

#include <cstdint>
#include <filesystem>
#include <glm/glm.hpp>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "engine/scene/behaviour.h"
#include "engine/scene/camera.h"
#include "engine/scene/camera_path.h"
#include "engine/scene/light.h"
#include "engine/scene/material.h"
#include "engine/scene/mesh.h"
#include "engine/scene/transform.h"
#include "engine/scene/volume.h"

namespace lantern {

// A mesh placed in the world with one material.
struct Instance {
  std::string name;
  std::uint32_t mesh = 0;      // index into Level::meshes
  std::uint32_t material = 0;  // index into Level::materials
  Transform transform;         // world TRS (decomposed from `world`)
  glm::mat4 world{1.0f};       // exact world matrix (glTF nodes may carry shear)
  std::optional<Behaviour> behaviour;
};

struct EnvironmentMap {
  std::filesystem::path path;  // EXR/HDR, equirectangular; read by the runtime (OpenImageIO)
  float intensity = 1.0f;      // radiance multiplier
  glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};
};

struct Level {
  std::string name;              // file stem
  std::filesystem::path source;  // the file it came from
  std::vector<Mesh> meshes;
  std::vector<Material> materials;
  std::vector<ImageRef> images;
  std::vector<Instance> instances;
  std::vector<Light> lights;
  std::vector<Volume> volumes;  // participating media; empty: no volume work at all
  Camera camera;
  bool has_camera = false;  // false: the loader framed the scene with a default camera
  std::vector<CameraPath> paths;
  std::string camera_path;  // the path the camera follows by default; empty = static
  std::optional<EnvironmentMap> environment;
  // Free-form settings (nested JSON objects flattened to "a.b" keys, values as text, the same
  // form as `--set KEY=VALUE`); lighting validates them.
  std::map<std::string, std::string> settings;
  std::filesystem::path budgets;  // optional budget file for `lantern bench`; empty = none

  const CameraPath* find_path(std::string_view path_name) const {
    for (const CameraPath& p : paths)
      if (p.name == path_name) return &p;
    return nullptr;
  }
};

}  // namespace lantern
