// Scene extraction for the GPU (lighting/scene/scene_data.h), on the CPU: emissive triangles and
// analytic lights become light records with stable ids and power by the documented formulas,
// instances point at their first emissive light, and a negative determinant flips the winding.
#include "lighting/scene/scene_data.h"

#include <gtest/gtest.h>

#include <glm/glm.hpp>
#include <set>

#include "engine/level/level_loader.h"
#include "engine/level/primitives.h"
#include "lighting/scene/scene_buffers.h"
#include "shared/color.h"
#include "shared/common_math.h"

namespace lantern {
namespace {

using lighting::build_scene_data;
using lighting::extract_light_emitters;
using lighting::kAnalyticLightIdBase;

TEST(SceneData, CornellLightsEmittersHaveStableIdsAndPower) {
  const Level level = load_level_argument("cornell_lights");
  const lighting::SceneData scene = build_scene_data(level);
  std::size_t emissive = 0;
  for (const Instance& inst : level.instances) {
    if (level.materials[inst.material].emissive()) {
      emissive += level.meshes[inst.mesh].triangle_count();
    }
  }
  ASSERT_GT(emissive, 0u);
  EXPECT_EQ(scene.emissive_triangles, emissive);
  ASSERT_EQ(scene.lights.lights().size(), emissive + level.lights.size());
  const std::vector<std::uint64_t>& ids = scene.lights.stable_ids();
  EXPECT_EQ(std::set<std::uint64_t>(ids.begin(), ids.end()).size(), ids.size());

  // Every instance's first light is its triangle 0, id (instance << 32 | 0).
  for (std::size_t i = 0; i < level.instances.size(); ++i) {
    const std::uint32_t first = scene.instances[i].bvh.y;
    if (!level.materials[level.instances[i].material].emissive()) {
      EXPECT_EQ(first, gpu::kInvalidLight);
      continue;
    }
    ASSERT_LT(first, ids.size());
    EXPECT_EQ(ids[first], static_cast<std::uint64_t>(i) << 32);
  }
  // The point light: 4 pi luminance(I), id in the analytic range.
  const Light& bulb = level.lights.at(0);
  const std::vector<lighting::LightEmitter> emitters =
      extract_light_emitters(level, scene.scene_radius());
  const lighting::LightEmitter& last = emitters.back();
  EXPECT_EQ(last.stable_id, kAnalyticLightIdBase | 0u);
  EXPECT_EQ(gpu::light_kind(last.light), gpu::kLightPoint);
  EXPECT_FLOAT_EQ(last.power, 4.0f * gpu::kPi * gpu::luminance(bulb.color * bulb.intensity));
}

// One 2x2 plane (area 4, two triangles, facing +Y) with emission L: each triangle's power is
// luminance(L) * 2 * pi and its front normal is +Y, also under a mirror in x (glTF: a negative
// determinant makes clockwise the front winding, so the lit side stays +Y).
TEST(SceneData, EmissiveTrianglePowerAndFrontFace) {
  Level level;
  level.meshes.push_back(make_plane(glm::vec2(2.0f, 2.0f)));
  Material m;
  m.emissive_factor = glm::vec3(1.0f, 2.0f, 3.0f);
  m.emissive_strength = 2.0f;
  level.materials.push_back(m);
  Instance plain;
  level.instances.push_back(plain);
  Instance mirrored;
  mirrored.world = glm::mat4(1.0f);
  mirrored.world[0][0] = -1.0f;  // mirror x: det < 0, plane still at y = 0
  level.instances.push_back(mirrored);

  const std::vector<lighting::LightEmitter> emitters = extract_light_emitters(level, 1.0f);
  ASSERT_EQ(emitters.size(), 4u);
  const float expected_power = gpu::luminance(m.emitted_radiance()) * 2.0f * gpu::kPi;
  for (const lighting::LightEmitter& e : emitters) {
    EXPECT_EQ(gpu::light_kind(e.light), gpu::kLightTriangle);
    EXPECT_NEAR(e.power, expected_power, 1e-4f * expected_power);
    const glm::vec3 n = glm::cross(glm::vec3(e.light.p1), glm::vec3(e.light.p2));
    // glTF: a mirroring transform keeps the front face on the same side (it flips the winding).
    EXPECT_GT(n.y, 0.0f) << "stable id " << e.stable_id;
  }
  EXPECT_EQ(emitters[2].stable_id, (1ull << 32) | 0u);
}

// The gloss bound ReSTIR's bsdf_min_gloss gate reads: a material's factors, its roughness
// taken as 0 where a metallic-roughness texture scales it, and the level's glossiest material.
TEST(SceneData, MaxGlossBoundsEverySurfaceOfTheLevel) {
  gpu::GpuMaterial rough{};
  rough.params = glm::vec4(0.8f, 0.0f, 0.5f, 0.0f);
  rough.textures = glm::uvec4(gpu::kNoTexture);
  EXPECT_FLOAT_EQ(lighting::material_max_gloss(rough), 0.5f * 0.5f * 0.2f);
  gpu::GpuMaterial textured = rough;
  textured.textures.y = 0;  // a metallic-roughness texture: roughness down to 0
  EXPECT_FLOAT_EQ(lighting::material_max_gloss(textured), 0.25f);
  gpu::GpuMaterial metal = rough;
  metal.params.y = 1.0f;
  EXPECT_FLOAT_EQ(lighting::material_max_gloss(metal), 1.0f);

  Level level;
  level.meshes.push_back(make_plane(glm::vec2(2.0f, 2.0f)));
  Material wall;
  wall.roughness = 0.9f;
  wall.metallic = 0.0f;
  level.materials.push_back(wall);
  level.instances.push_back(Instance{});
  const float dielectric = build_scene_data(level).max_gloss;
  EXPECT_NEAR(dielectric, 0.5f * wall.specular_factor * 0.1f, 1e-6f);
  Material post = wall;
  post.metallic = 1.0f;
  level.materials.push_back(post);
  EXPECT_FLOAT_EQ(build_scene_data(level).max_gloss, 1.0f) << "one metal opens the gate";
}

}  // namespace
}  // namespace lantern

namespace lantern::lighting {
namespace {

// The scene table: exactly the device-built rows (the TLAS) have no CPU bytes to upload.
TEST(SceneBuffers, OnlyDeviceBuiltRowsHaveNoBytes) {
  for (const SceneBufferRow& row : kSceneBuffers) {
    EXPECT_EQ(row.bytes == nullptr, row.kind == SceneResourceKind::AccelerationStructure)
        << row.graph_name;
  }
}

}  // namespace
}  // namespace lantern::lighting
