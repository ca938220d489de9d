// What a level contains, for `lantern info`: counts of entities, meshes, triangles, lights by
// kind, emitters and paths. What the engine enables for the level is added by lighting later
// (extension point: LevelSummary::enabled, free-form sections rendered after the contents).
#pragma once

#include <cstdint>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "engine/scene/level.h"

namespace lantern {

struct LevelSummary {
  std::string name;
  std::string source;
  std::uint64_t entities = 0;  // instances + lights + volumes + the camera
  std::uint64_t instances = 0;
  std::uint64_t meshes = 0;
  std::uint64_t triangles = 0;  // over all instances
  std::uint64_t emissive_triangles = 0;
  std::uint64_t point_lights = 0;
  std::uint64_t spot_lights = 0;
  std::uint64_t directional_lights = 0;
  std::uint64_t volumes = 0;  // Level::volumes (grids, voxels, memory: enabled["volumes"])
  std::uint64_t behaviours = 0;
  bool environment_map = false;
  std::string camera_path;
  struct Path {
    std::string name;
    float duration = 0.0f;
    std::size_t keys = 0;
    bool loop = false;
  };
  std::vector<Path> paths;
  // Filled by later layers (lighting): section name -> JSON object (sampling structures, shader
  // variants, memory per part). Printed as-is after the contents.
  std::map<std::string, nlohmann::json> enabled;
};

LevelSummary summarize(const Level& level);
nlohmann::json to_json(const LevelSummary& summary);
std::string to_text(const LevelSummary& summary);

}  // namespace lantern
