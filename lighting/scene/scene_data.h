// The CPU-side GPU records of a static level: vertices, indices, materials, instances, the
// scene BVH and the light table (emissive triangles + analytic lights), ready to upload
// (lighting/scene/gpu_scene.h). Built once from a Level; no Vulkan here.
#pragma once

#include <cstdint>
#include <vector>

#include "engine/scene/level.h"
#include "lighting/bvh/scene_bvh.h"
#include "lighting/lights/light_table.h"
#include "shared/scene.h"

namespace lantern::lighting {

// Stable light ids: emissive triangle t of instance i is (i << 32 | t); analytic light k of the
// level is (kAnalyticLightIdBase | k), a range no instance index reaches.
inline constexpr std::uint64_t kAnalyticLightIdBase = 0xffffffffull << 32;

struct SceneData {
  std::vector<gpu::GpuVertex> vertices;  // all meshes, mesh by mesh (object space)
  std::vector<std::uint32_t> indices;    // mesh-relative vertex indices, mesh by mesh
  std::vector<gpu::GpuMaterial> materials;
  std::vector<gpu::GpuInstance> instances;  // one per Level instance, same order as the BVH's
  SceneBvh bvh;
  LightTable lights;
  std::uint32_t emissive_triangles = 0;
  glm::vec3 bounds_min{0.0f};  // world-space box of all instances
  glm::vec3 bounds_max{0.0f};
  // Radius of the world box's bounding sphere (>= a small positive floor): sizes directional
  // lights' shadow rays and their power proxy.
  float scene_radius() const;
};

// The light records of a level: one per emissive triangle (world space, one-sided) and one per
// point/spot/directional light, with power = flux (triangles: luminance(L) * area * pi;
// point/spot: 4 pi luminance(I)) or, for directional lights, luminance(E) * pi * scene_radius^2.
std::vector<LightEmitter> extract_light_emitters(const Level& level, float scene_radius);

// The emissive triangles of instance `instance` (a Level instance index) placed by `world`, with
// emitted radiance `radiance`, appended to `out` in triangle order (ids as above).
void append_triangle_emitters(const Mesh& mesh, const glm::mat4& world, const glm::vec3& radiance,
                              std::uint32_t instance, std::vector<LightEmitter>& out);

// Analytic light `index` of the level (point, spot or directional) as a light record:
// `intensity` = colour x intensity; spot cones in radians; `range` (0 = none) goes to p2.w.
LightEmitter analytic_emitter(std::uint32_t index, LightType type, const glm::vec3& position,
                              const glm::vec3& direction, const glm::vec3& intensity,
                              float inner_cone, float outer_cone, float range, float scene_radius);

// The BVH placement of every Level instance (user_id = instance index): instances whose
// behaviour never moves them (none, or flicker) are declared fixed, so the BVH merges them.
std::vector<BvhInstanceDesc> bvh_instance_descs(const Level& level);

// Builds everything; throws lantern::InputError on bad level data (bad indices, singular
// transforms, out-of-range material or mesh references).
SceneData build_scene_data(const Level& level);

}  // namespace lantern::lighting
