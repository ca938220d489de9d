// Interactive lights of `lantern play`, in every level: a flashlight (a spot light attached to the
// camera entity, F), light groups on and off (L: the level's analytic lights, K: its emissive
// surfaces), and point lights spawned where the camera looks (Space, a CPU ray cast through the
// scene BVH). The level gets the play lights appended before the World is made (so every light
// keeps a stable id = its index in Level::lights); switching a light on or off adds or removes
// its entity in the World, and ReSTIR's previous->current light remap does the rest.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <optional>
#include <vector>

#include "engine/ecs/entity.h"
#include "engine/scene/level.h"

namespace lantern {
class World;
}
namespace lantern::lighting {
class GpuScene;
}

namespace lantern::app {

inline constexpr std::uint32_t kSpawnSlots = 8;

// Scale of the level: its world bounding-sphere radius (>= 0.1).
float level_radius(const Level& level);

// Appends the flashlight and kSpawnSlots spawn lights to `level`, sized for display at
// `exposure` (the auto exposure of the unmodified level): a spawned light lights surfaces at a
// few percent of the level radius to about mid grey.
struct PlayLightSlots {
  std::uint32_t level_lights = 0;  // the level's own lights: [0, level_lights)
  std::uint32_t flashlight = 0;    // index of the flashlight in Level::lights
  std::uint32_t first_spawn = 0;   // kSpawnSlots indices from here
};
PlayLightSlots add_play_lights(Level& level, float exposure);

class PlayLights {
 public:
  // Removes the play lights' entities the World made (they start switched off) and registers
  // play.attach_to_camera (Simulate: keeps the flashlight on the camera).
  PlayLights(World& world, const PlayLightSlots& slots);

  void toggle_flashlight();
  void toggle_level_lights();       // L: analytic lights of the level
  void toggle_emissive_surfaces();  // K: emissive instances (emission scale 0 / restored)
  // Spawns a point light `offset` in front of the surface hit by the camera's centre ray;
  // false when the ray hits nothing. The oldest spawned light is reused after kSpawnSlots.
  bool spawn_light(const lighting::GpuScene& scene);
  void clear_spawned();

  bool flashlight_on() const { return flashlight_.has_value(); }
  bool level_lights_on() const { return level_lights_on_; }
  bool emissive_on() const { return emissive_on_; }
  std::uint32_t spawned() const { return spawned_count_; }
  std::optional<glm::vec3> last_spawn() const { return last_spawn_; }

 private:
  Entity add_light_entity(std::uint32_t index);

  World& world_;
  PlayLightSlots slots_;
  std::optional<Entity> flashlight_;
  bool level_lights_on_ = true;
  bool emissive_on_ = true;
  std::vector<std::optional<Entity>> spawn_;
  std::uint32_t next_spawn_ = 0;
  std::uint32_t spawned_count_ = 0;
  std::optional<glm::vec3> last_spawn_;
};

}  // namespace lantern::app
