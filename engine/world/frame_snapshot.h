// The immutable result of a frame's Extract phase: everything the renderer needs from the world,
// copied out so rendering can proceed while the next frame simulates.
//
// Conventions (Vulkan):
// - View space is right-handed: the camera looks down -Z, +Y is up, +X right.
// - `projection` maps view space to Vulkan clip space: x right, y DOWN (NDC y = -1 is the top row
//   of the image, matching pixel (0,0) top-left), depth z/w in [0, 1] with 0 at the near plane and
//   1 at the far plane (or at infinity when zfar is 0: an infinite far plane).
// - Matrices are glm column-major, column vectors: clip = projection * view * world * p.
// Instances, lights and volumes are sorted by stable id. Plain 4-byte fields only in the per-element
// structs, so two snapshots can be compared with memcmp.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <memory>
#include <vector>

#include "engine/scene/level.h"

namespace lantern {

struct SnapshotCamera {
  glm::vec3 position{0.0f};
  float yfov = 0.8f;  // vertical field of view, radians
  glm::quat orientation{1.0f, 0.0f, 0.0f, 0.0f};
  float aspect = 1.0f;  // width / height
  float znear = 0.05f;
  float zfar = 0.0f;  // 0 = infinite far plane
  float pad0 = 0.0f;
  glm::mat4 view{1.0f};        // world → view
  glm::mat4 projection{1.0f};  // view → Vulkan clip (see above)
};
static_assert(sizeof(SnapshotCamera) == 12 * 4 + 2 * 64);

struct SnapshotInstance {
  glm::mat4 object_to_world{1.0f};
  glm::mat4 prev_object_to_world{1.0f};  // equals object_to_world on frame 0 and when static
  std::uint32_t stable_id = 0;           // index in Level::instances
  std::uint32_t mesh = 0;                // index in Level::meshes
  std::uint32_t material = 0;            // index in Level::materials
  float emission_scale = 1.0f;           // multiplies the material's emission (flicker)
};
static_assert(sizeof(SnapshotInstance) == 2 * 64 + 16);

struct SnapshotLight {
  glm::vec3 position{0.0f};                // world space (unused for directional lights)
  std::uint32_t stable_id = 0;             // index in Level::lights
  glm::vec3 direction{0.0f, 0.0f, -1.0f};  // world space, unit: where the light shines
  float intensity = 0.0f;   // current: Level intensity × flicker (W/sr, or W/m² if directional)
  glm::vec3 color{1.0f};    // linear RGB multiplier
  std::uint32_t type = 0;   // LightType
  float range = 0.0f;       // 0 = pure inverse-square falloff
  float inner_cone = 0.0f;  // spot, radians
  float outer_cone = 0.0f;  // spot, radians
  float pad0 = 0.0f;
};
static_assert(sizeof(SnapshotLight) == 16 * 4);

struct SnapshotVolume {
  glm::mat4 object_to_world{1.0f};       // the placement; the grid's index-to-world comes first
  glm::mat4 prev_object_to_world{1.0f};  // equals object_to_world on frame 0 and when static
  std::uint32_t stable_id = 0;           // index in Level::volumes
  std::uint32_t pad0 = 0;
  std::uint32_t pad1 = 0;
  std::uint32_t pad2 = 0;
};
static_assert(sizeof(SnapshotVolume) == 2 * 64 + 16);

struct FrameSnapshot {
  std::uint64_t frame_index = 0;
  double time = 0.0;  // seconds since the start at the end of the frame: the time poses are for
  double dt = 0.0;
  std::uint64_t seed = 0;
  // No usable history: frame 0, or a cut was requested (World::request_camera_cut). Temporal
  // passes must drop their history on such frames.
  bool camera_cut = true;
  SnapshotCamera camera;
  SnapshotCamera prev_camera;  // equals camera on frame 0
  std::vector<SnapshotInstance> instances;
  std::vector<SnapshotLight> lights;
  std::vector<SnapshotVolume> volumes;  // empty for a level without media
  std::shared_ptr<const Level> level;   // meshes, materials, lights and volumes the ids index
};

// `s` held still: the same poses again, no motion since the previous frame, history kept (a static
// scene in which only the random numbers change: what converged and bias renders average).
inline FrameSnapshot frozen(const FrameSnapshot& s) {
  FrameSnapshot f = s;
  f.camera_cut = false;
  f.prev_camera = f.camera;
  for (SnapshotInstance& i : f.instances) i.prev_object_to_world = i.object_to_world;
  for (SnapshotVolume& v : f.volumes) v.prev_object_to_world = v.object_to_world;
  return f;
}

// Resources the Extract system uses: the latest snapshot, and a pending camera-cut request.
struct FrameSnapshotSlot {
  std::shared_ptr<const FrameSnapshot> latest;
};
struct CameraCutRequest {
  bool pending = false;
};

}  // namespace lantern
