// Imports a glTF 2.0 file (.gltf or .glb, through Debian's tinygltf) into a Level: meshes,
// metallic-roughness materials (+ emissive strength, specular), image references, instances,
// KHR_lights_punctual lights, the first camera node and that camera's animation as a path, and
// each animated mesh node as a path of the level that its instances follow (follow_path).
#pragma once

#include <filesystem>
#include <glm/glm.hpp>
#include <optional>

#include "engine/level/mesh_validation.h"
#include "engine/scene/level.h"

namespace lantern {

struct GltfImport {
  std::optional<Camera> camera;           // the first camera node, if any
  std::optional<CameraPath> camera_path;  // sampled from an animation of that node, if any
  std::size_t first_instance = 0;         // the instances this import appended: [first, end)
  std::size_t first_light = 0;
};

// Appends the file's content to `level`, every node placed under `placement` (world matrix).
// Animated mesh nodes add paths named "<file stem>/<node name or index>" to `level.paths`.
// Throws InputError naming the file and the node/mesh/accessor for bad input.
GltfImport import_gltf(const std::filesystem::path& file, const glm::mat4& placement, Level& level,
                       LoadDiagnostics& diagnostics);

}  // namespace lantern
