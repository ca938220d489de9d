// The ECS components and resources a Level becomes (see instantiate.h). Meshes, materials and
// light parameters stay in the immutable Level; components hold indices into it plus the state
// that changes per frame.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <memory>
#include <string>

#include "engine/scene/behaviour.h"
#include "engine/scene/camera.h"
#include "engine/scene/level.h"
#include "engine/scene/transform.h"

namespace lantern {

// The pose state is the scene's `Transform` (TRS), written by the behaviour systems.

// Which array of the Level an entity came from; stable ids are unique per kind.
enum class EntityKind : std::uint32_t { Instance = 0, Light = 1, Volume = 2 };

// The entity's id for the life of the world: its index in Level::instances, Level::lights or
// Level::volumes.
// Renderers key temporal data (previous↔current remaps, G-buffer ids) on it.
struct StableId {
  EntityKind kind = EntityKind::Instance;
  std::uint32_t value = 0;
};

// Object-to-world matrix of an instance, final for this frame (written in the Transform phase).
struct WorldMatrix {
  glm::mat4 object_to_world{1.0f};
};

// Last frame's WorldMatrix (equal to the current one on frame 0 and for static instances).
struct PreviousTransform {
  glm::mat4 object_to_world{1.0f};
};

// Tag: the instance's WorldMatrix follows its Transform (it has a moving behaviour). Static
// instances keep the Level's exact world matrix (glTF nodes may carry shear that TRS drops).
struct DynamicTransform {};

struct MeshRef {
  std::uint32_t index = 0;  // into Level::meshes
};
struct MaterialRef {
  std::uint32_t index = 0;  // into Level::materials
};

// An analytic light; its type, colour, range and cones stay in Level::lights[index]. Position and
// orientation are the entity's Transform (translation, rotation).
struct LightComponent {
  std::uint32_t index = 0;
};

// A participating medium; its grid, coefficients and phase function stay in
// Level::volumes[index]. Its placement is the entity's Transform (WorldMatrix = the placement
// matrix, applied after the grid's own index-to-world); it moves like an instance.
struct VolumeComponent {
  std::uint32_t index = 0;
};

// Multiplier on emitted power this frame (lights: intensity; instances: emission). 1 unless a
// flicker behaviour drives it.
struct EmissionScale {
  float value = 1.0f;
};

// Behaviours with the initial state they animate from. Systems evaluate them at absolute time
// (no accumulation), so a frame's pose depends only on its time, never on earlier rounding.
struct RotateComponent {
  RotateBehaviour params;
  glm::quat base_rotation{1.0f, 0.0f, 0.0f, 0.0f};
};
struct OrbitComponent {
  OrbitBehaviour params;
};
struct FlickerComponent {
  FlickerBehaviour params;
};
struct FollowPathComponent {
  FollowPathBehaviour params;
  std::uint32_t path = 0;  // index into Level::paths (resolved at instantiation)
};

// The camera's pose and lens, written in Simulate (by the camera path system when one is active).
struct CameraComponent {
  Camera camera;
};

// The camera of this frame and of the last one, latched in the Transform phase.
struct CameraHistory {
  Camera current;
  Camera previous;
};

// --- resources ---------------------------------------------------------------------------------

// The immutable Level every index refers to: `registry.ctx().get<LevelResource>()`.
using LevelResource = std::shared_ptr<const Level>;

// The camera path the camera follows; empty = static camera.
struct ActiveCameraPath {
  std::string name;
};

// Settings fixed for the life of a world.
struct WorldSettings {
  std::uint64_t seed = 1;          // root of every random number the world systems draw
  float aspect = 640.0f / 360.0f;  // output width / height, used when the level's camera has none
};

}  // namespace lantern
