// Test levels and a frame runner (see world_levels.h).
#include "world_levels.h"

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "engine/level/level_loader.h"

namespace lantern::test {
namespace {

// Every behaviour kind, on instances and lights, with a looping follow_path at double speed (it
// wraps within 100 frames at 60 Hz) and a camera on a path with fov keys.
constexpr const char* kAnimatedLevel = R"json({
  "paths": {
    "fly": { "keys": [
      { "time": 0.0, "position": [0, 1, 4], "target": [0, 0.5, 0], "yfov_deg": 40 },
      { "time": 0.7, "position": [1.5, 1.4, 3], "target": [0, 0.5, 0], "yfov_deg": 50 },
      { "time": 1.9, "position": [-1, 0.8, 3.5], "target": [0, 0.3, 0], "yfov_deg": 45 } ] },
    "lap": { "loop": true, "keys": [
      { "time": 0.0, "position": [-1, 0.5, 0], "target": [0, 0.5, 0] },
      { "time": 0.3, "position": [0, 0.5, 1], "target": [0, 0.5, 0] },
      { "time": 0.6, "position": [1, 0.5, 0], "target": [0, 0.5, 0] },
      { "time": 0.9, "position": [-1, 0.5, 0], "target": [0, 0.5, 0] } ] }
  },
  "behaviours": {
    "spin":   { "type": "rotate", "axis": [0.3, 1, 0.2], "speed_deg": 140 },
    "circle": { "type": "orbit", "center": [0, 1.5, 0], "radius": 0.8, "speed_deg": 75, "phase_deg": 30 },
    "candle": { "type": "flicker", "min": 0.3, "max": 1.2, "rate": 9, "seed": 7 },
    "ride":   { "type": "follow_path", "path": "lap", "speed": 2, "loop": true }
  },
  "primitives": [
    { "type": "plane", "name": "floor", "size": [4, 4] },
    { "type": "box", "name": "spinner", "size": [0.5, 0.5, 0.5], "translation": [0.5, 0.25, -0.5],
      "scale": [1, 2, 1], "behaviour": "spin" },
    { "type": "sphere", "name": "rider", "radius": 0.2, "mesh": "ico", "subdivisions": 1, "behaviour": "ride" },
    { "type": "box", "name": "mover", "size": [0.3, 0.3, 0.3], "behaviour": "circle" }
  ],
  "lights": [
    { "type": "point", "name": "candle", "position": [0, 1, 0], "intensity": 3, "behaviour": "candle" },
    { "type": "point", "name": "firefly", "position": [0, 1.5, 0], "intensity": 1, "behaviour": "circle" },
    { "type": "spot", "name": "beam", "position": [0, 3, 0], "target": [0, 0, 0], "intensity": 10,
      "inner_cone_deg": 20, "outer_cone_deg": 35, "behaviour": { "type": "rotate", "axis": [1, 0, 0], "speed_deg": 45 } },
    { "type": "point", "name": "flicker_two", "position": [1, 1, 1], "intensity": 2, "behaviour": "candle" }
  ],
  "camera": { "position": [0, 1, 4], "target": [0, 0.5, 0], "yfov_deg": 40, "path": "fly" }
})json";

}  // namespace

std::shared_ptr<const Level> cornell_level() {
  return std::make_shared<const Level>(load_level_argument("cornell_lights"));
}

std::shared_ptr<const Level> animated_level() {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("lantern_world_test_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::filesystem::path file = dir / "animated.json";
  std::ofstream(file) << kAnimatedLevel;
  auto level = std::make_shared<const Level>(load_level_argument(file.string()));
  std::filesystem::remove_all(dir);
  return level;
}

std::vector<FrameSnapshot> run_frames(const std::shared_ptr<const Level>& level,
                                      const WorldOptions& options, int frames) {
  World world(level, options);
  std::vector<FrameSnapshot> out;
  out.reserve(static_cast<std::size_t>(frames));
  for (int i = 0; i < frames; ++i) out.push_back(world.step());
  return out;
}

}  // namespace lantern::test
