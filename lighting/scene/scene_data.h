// The CPU-side GPU records of a static level: vertices, indices, materials, instances, the
// scene BVH and the light table (emissive triangles + analytic lights), ready to upload
// (lighting/scene/gpu_scene.h). Built once from a Level; no Vulkan here.
#pragma once

#include <cstdint>
#include <vector>

#include "engine/scene/level.h"
#include "lighting/bvh/scene_bvh.h"
#include "lighting/lights/light_table.h"
#include "lighting/textures/texture_set.h"
#include "shared/scene.h"
#include "shared/textures.h"

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
  // Material textures (empty without any) and the textured emissive triangles: per Level instance
  // the first GpuTexturedEmitter record of its triangles (kNoTexture: its emission is not
  // textured); per record the emissive texture's mean over the triangle (the power weight,
  // integrated once at load).
  TextureSet textures;
  std::vector<gpu::GpuTexturedEmitter> textured_emitters;
  std::vector<std::uint32_t> instance_emitter_record;
  std::vector<glm::vec3> textured_emitter_means;
  double textured_emitter_ms = 0.0;  // wall time of integrating the means at load
  glm::vec3 bounds_min{0.0f};  // world-space box of all instances
  glm::vec3 bounds_max{0.0f};
  // Radius of the world box's bounding sphere (>= a small positive floor): sizes directional
  // lights' shadow rays and their power proxy.
  float scene_radius() const;
};

// The light records of a level: one per emissive triangle (world space, one-sided) and one per
// point/spot/directional light, with power = flux (triangles: luminance(L) * area * pi;
// point/spot: 4 pi luminance(I)) or, for directional lights, luminance(E) * pi * scene_radius^2.
// `scene` (may be null: no textured emission) supplies the textured triangles' records and means.
std::vector<LightEmitter> extract_light_emitters(const Level& level, float scene_radius,
                                                 const SceneData* scene = nullptr);

// The textured-emission records of one instance's triangles: record first_record + t is
// triangle t's; means[first_record + t] its texture mean.
struct EmitterTextureRange {
  std::uint32_t first_record = gpu::kNoTexture;
  const std::vector<glm::vec3>* means = nullptr;
};

// The emissive triangles of instance `instance` (a Level instance index) placed by `world`, with
// emitted radiance `radiance`, appended to `out` in triangle order (ids as above). With a
// texture range, each record names its GpuTexturedEmitter (radiance.w) and its power is weighted
// by the texture's mean over the triangle (a black triangle has power 0: never sampled).
void append_triangle_emitters(const Mesh& mesh, const glm::mat4& world, const glm::vec3& radiance,
                              std::uint32_t instance, std::vector<LightEmitter>& out,
                              EmitterTextureRange texture = {});
// The range of Level instance `instance` in `scene` (first_record kNoTexture if untextured).
EmitterTextureRange emitter_texture_range(const SceneData& scene, std::size_t instance);

// Analytic light `index` of the level (point, spot or directional) as a light record:
// `intensity` = colour x intensity; spot cones in radians; `range` (0 = none) goes to p2.w.
LightEmitter analytic_emitter(std::uint32_t index, LightType type, const glm::vec3& position,
                              const glm::vec3& direction, const glm::vec3& intensity,
                              float inner_cone, float outer_cone, float range, float scene_radius);

// BvhInstanceDesc::flags of a level instance: kBvhInstanceAlphaTested for an alpha-tested
// material (shadow and closest-hit rays then ask the material's cutout at each hit).
std::uint32_t instance_bvh_flags(const Level& level, const Instance& instance);

// The BVH placement of every Level instance (user_id = instance index): instances whose
// behaviour never moves them (none, or flicker) and whose material is not alpha-tested are
// declared fixed, so the BVH merges them.
std::vector<BvhInstanceDesc> bvh_instance_descs(const Level& level);

// Builds everything; throws lantern::InputError on bad level data (bad indices, singular
// transforms, out-of-range material or mesh references).
SceneData build_scene_data(const Level& level);

}  // namespace lantern::lighting
