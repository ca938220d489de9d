// JSON level format: every section of tests/level/data/all_sections.json arrives in the Level
// with the documented units and conventions; cornell_lights and name resolution work.
#include <gtest/gtest.h>

#include <cstdlib>
#include <glm/gtc/matrix_transform.hpp>

#include "engine/level/level_loader.h"
#include "engine/scene/level_summary.h"
#include "tests/level/test_files.h"

namespace lantern {
namespace {

const Instance& instance(const Level& level, const std::string& name) {
  for (const Instance& i : level.instances)
    if (i.name == name) return i;
  ADD_FAILURE() << "no instance " << name;
  return level.instances.front();
}

const Light& light(const Level& level, const std::string& name) {
  for (const Light& l : level.lights)
    if (l.name == name) return l;
  ADD_FAILURE() << "no light " << name;
  return level.lights.front();
}

void expect_near(glm::vec3 a, glm::vec3 b, float eps = 1e-5f) {
  EXPECT_NEAR(a.x, b.x, eps);
  EXPECT_NEAR(a.y, b.y, eps);
  EXPECT_NEAR(a.z, b.z, eps);
}

class AllSections : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    level_ = new Level(load_level(test::data_dir() / "all_sections.json"));
  }
  static void TearDownTestSuite() { delete level_; }
  static Level* level_;
};
Level* AllSections::level_ = nullptr;

TEST_F(AllSections, MaterialsKeepEveryField) {
  const Level& l = *level_;
  const Material& matte = l.materials[instance(l, "floor").material];
  EXPECT_EQ(matte.name, "matte");
  EXPECT_EQ(matte.base_color, glm::vec4(0.5f, 0.25f, 0.125f, 1.0f));
  EXPECT_FLOAT_EQ(matte.roughness, 0.75f);
  EXPECT_FLOAT_EQ(matte.specular_factor, 0.0f);
  EXPECT_FALSE(matte.emissive());
  const Material& lamp = l.materials[instance(l, "ico").material];
  EXPECT_TRUE(lamp.double_sided);
  expect_near(lamp.emitted_radiance(), glm::vec3(8.0f, 4.0f, 2.0f));
  expect_near(lamp.specular_color, glm::vec3(0.9f));
  const Material& inline_mat = l.materials[instance(l, "ball").material];
  EXPECT_FLOAT_EQ(inline_mat.metallic, 1.0f);
  EXPECT_FLOAT_EQ(inline_mat.roughness, 0.1f);
}

TEST_F(AllSections, PrimitivesArePlacedWithTheirTransforms) {
  const Level& l = *level_;
  const Instance& crate = instance(l, "crate");
  const Mesh& box = l.meshes[crate.mesh];
  EXPECT_EQ(box.triangle_count(), 12u);
  expect_near(box.bounds.extent(), glm::vec3(1, 2, 3));
  expect_near(crate.transform.translation, glm::vec3(1, 1, 0));
  // rotation_deg [0, 90, 0]: local +X maps to world -Z.
  expect_near(crate.transform.rotation * glm::vec3(1, 0, 0), glm::vec3(0, 0, -1));
  expect_near(glm::vec3(crate.world * glm::vec4(1, 0, 0, 1)), glm::vec3(1, 1, -1));
  const Mesh& floor = l.meshes[instance(l, "floor").mesh];
  expect_near(floor.bounds.extent(), glm::vec3(20, 0, 10));
  for (const glm::vec3& n : floor.normals) expect_near(n, glm::vec3(0, 1, 0));
  // An inward box's normals point at its centre.
  const Mesh& room = l.meshes[instance(l, "room").mesh];
  for (std::size_t i = 0; i < room.positions.size(); ++i)
    EXPECT_LT(glm::dot(room.normals[i], room.positions[i]), 0.0f);
  EXPECT_EQ(l.meshes[instance(l, "ball").mesh].triangle_count(), 8u * 4u * 2u - 2u * 8u);
  EXPECT_EQ(l.meshes[instance(l, "ico").mesh].triangle_count(), 80u);
}

TEST_F(AllSections, EmissiveQuadGridIsBinnedByRadiance) {
  const Level& l = *level_;
  std::size_t quads = 0;
  std::vector<float> radiances;
  for (const Instance& i : l.instances) {
    if (i.name != "wall") continue;
    quads += l.meshes[i.mesh].triangle_count() / 2;
    radiances.push_back(l.materials[i.material].emissive_strength);
    // The grid lies in z = -4 and faces +Z (cross(u, v)).
    for (const glm::vec3& n : l.meshes[i.mesh].normals) expect_near(n, glm::vec3(0, 0, 1));
    EXPECT_NEAR(l.meshes[i.mesh].bounds.min.z, -4.0f, 1e-6f);
  }
  EXPECT_EQ(quads, 12u);
  ASSERT_EQ(radiances.size(), 4u);  // levels: 4
  std::sort(radiances.begin(), radiances.end());
  EXPECT_NEAR(radiances.front(), 1.0f, 1e-4f);
  EXPECT_NEAR(radiances.back(), 1000.0f, 1e-1f);
}

TEST_F(AllSections, LightsUseRadiometricUnits) {
  const Level& l = *level_;
  const Light& p = light(l, "p");
  EXPECT_EQ(p.type, LightType::Point);
  EXPECT_FLOAT_EQ(p.intensity, 12.0f);
  EXPECT_FLOAT_EQ(p.range, 20.0f);
  expect_near(p.color, glm::vec3(1, 0.9f, 0.8f));
  expect_near(p.position, glm::vec3(0, 3, 0));
  ASSERT_TRUE(p.behaviour);
  const auto& flicker = std::get<FlickerBehaviour>(*p.behaviour);
  EXPECT_EQ(flicker, (FlickerBehaviour{0.25f, 1.5f, 6.0f, 42u}));
  const Light& s = light(l, "s");
  EXPECT_EQ(s.type, LightType::Spot);
  expect_near(s.direction(), glm::vec3(0, -1, 0));
  EXPECT_NEAR(s.inner_cone, glm::radians(20.0f), 1e-6f);
  EXPECT_NEAR(s.outer_cone, glm::radians(40.0f), 1e-6f);
  EXPECT_FLOAT_EQ(s.range, 0.0f);  // no range: inverse square
  const Light& d = light(l, "d");
  EXPECT_EQ(d.type, LightType::Directional);
  EXPECT_FLOAT_EQ(d.intensity, 2.5f);
  expect_near(d.direction(), glm::vec3(0, -1, 0));
}

TEST_F(AllSections, BehavioursAttachToInstancesAndLights) {
  const Level& l = *level_;
  const auto& orbit = std::get<OrbitBehaviour>(*instance(l, "crate").behaviour);
  expect_near(orbit.center, glm::vec3(1, 0, 1));
  EXPECT_FLOAT_EQ(orbit.radius, 2.5f);
  EXPECT_NEAR(orbit.speed, glm::radians(45.0f), 1e-6f);
  EXPECT_NEAR(orbit.phase, glm::radians(90.0f), 1e-6f);
  const auto& follow = std::get<FollowPathBehaviour>(*instance(l, "ico").behaviour);
  EXPECT_EQ(follow, (FollowPathBehaviour{"lift", 0.5f, false}));
  // An asset's behaviour applies to every instance and light it brought.
  const auto& rotate = std::get<RotateBehaviour>(*instance(l, "panel").behaviour);
  expect_near(rotate.axis, glm::vec3(0, 1, 0));  // normalised
  EXPECT_NEAR(rotate.speed, glm::radians(90.0f), 1e-6f);
  EXPECT_TRUE(light(l, "bulb").behaviour.has_value());
  EXPECT_EQ(behaviour_type_name(*light(l, "bulb").behaviour), std::string("rotate"));
}

TEST_F(AllSections, AssetsArePlacedAndKeepTheirUnits) {
  const Level& l = *level_;
  // lights_camera.gltf placed at x = 10 with scale 2: its bulb node at (1, 2, 3) lands at (12, 4,
  // 6).
  expect_near(light(l, "bulb").position, glm::vec3(12, 4, 6));
  EXPECT_FLOAT_EQ(light(l, "bulb").intensity, 5.0f);  // intensity is not scaled by placement
  const Instance& panel = instance(l, "panel");
  expect_near(glm::vec3(panel.world * glm::vec4(0, 0, 0, 1)), glm::vec3(10, 0, -4));
}

TEST_F(AllSections, CameraPathsEnvironmentSettingsBudgets) {
  const Level& l = *level_;
  EXPECT_TRUE(l.has_camera);
  expect_near(l.camera.position, glm::vec3(0, 1.5f, 8));
  expect_near(l.camera.forward(), glm::normalize(glm::vec3(0, -0.5f, -8)));
  EXPECT_NEAR(l.camera.yfov, glm::radians(60.0f), 1e-6f);
  EXPECT_FLOAT_EQ(l.camera.aspect, 2.0f);
  EXPECT_FLOAT_EQ(l.camera.znear, 0.2f);
  EXPECT_FLOAT_EQ(l.camera.zfar, 500.0f);
  EXPECT_EQ(l.camera_path, "tour");
  const CameraPath* tour = l.find_path("tour");
  ASSERT_NE(tour, nullptr);
  EXPECT_TRUE(tour->loop);
  ASSERT_EQ(tour->keys.size(), 4u);
  EXPECT_NEAR(*tour->keys[1].yfov, glm::radians(40.0f), 1e-6f);
  expect_near(tour->keys[1].orientation * glm::vec3(0, 0, -1), glm::vec3(-1, 0, 0));
  EXPECT_NE(l.find_path("lift"), nullptr);
  EXPECT_NE(l.find_path("fly"), nullptr);     // the asset's camera animation
  EXPECT_NE(l.find_path("market"), nullptr);  // the generator's path
  ASSERT_TRUE(l.environment);
  EXPECT_EQ(l.environment->path.filename(), "sky.hdr");
  EXPECT_FLOAT_EQ(l.environment->intensity, 0.5f);
  expect_near(l.environment->rotation * glm::vec3(1, 0, 0), glm::vec3(0, 0, -1));
  EXPECT_EQ(l.settings.at("exposure"), "-1.5");
  EXPECT_EQ(l.settings.at("restir.spatial_passes"), "2");
  EXPECT_EQ(l.settings.at("restir.bias_correction"), "pairwise");
  EXPECT_EQ(l.settings.at("restir.temporal"), "true");
  EXPECT_EQ(l.budgets.filename(), "budget.json");
}

TEST_F(AllSections, SummaryCountsWhatWasLoaded) {
  const Level& l = *level_;
  const LevelSummary s = summarize(l);
  std::uint64_t tris = 0, emissive = 0;
  for (const Instance& i : l.instances) {
    tris += l.meshes[i.mesh].triangle_count();
    if (l.materials[i.material].emissive()) emissive += l.meshes[i.mesh].triangle_count();
  }
  EXPECT_EQ(s.triangles, tris);
  EXPECT_EQ(s.emissive_triangles, emissive);
  EXPECT_GT(s.emissive_triangles, 12u * 2u);
  EXPECT_EQ(s.point_lights + s.spot_lights + s.directional_lights, l.lights.size());
  EXPECT_EQ(s.directional_lights, 2u);  // one in the JSON, one in the asset
  EXPECT_TRUE(s.environment_map);
  EXPECT_EQ(s.volumes, 0u);
  const nlohmann::json j = to_json(s);
  EXPECT_EQ(j["triangles"].get<std::uint64_t>(), tris);
  EXPECT_EQ(j["lights"]["total"].get<std::size_t>(), l.lights.size());
  EXPECT_EQ(j["paths"].size(), l.paths.size());
  EXPECT_NE(to_text(s).find("tour"), std::string::npos);
}

TEST(LevelFiles, CornellLightsLoads) {
  const Level l = load_level_argument("cornell_lights");
  const LevelSummary s = summarize(l);
  EXPECT_GE(s.emissive_triangles, 2u * 24u);  // a few dozen emissive quads
  EXPECT_EQ(s.point_lights, 1u);
  float lo = 1e30f, hi = 0.0f;
  for (const Material& m : l.materials)
    if (m.emissive()) {
      lo = std::min(lo, m.emissive_strength);
      hi = std::max(hi, m.emissive_strength);
    }
  EXPECT_GE(hi / lo, 1e4f * 0.999f);  // radiances span 10^4
  std::size_t moving = 0;
  for (const Instance& i : l.instances) moving += i.behaviour.has_value();
  EXPECT_GE(moving, 1u);
  EXPECT_TRUE(l.has_camera);
  EXPECT_TRUE(l.camera_path.empty());  // a static camera
  ASSERT_FALSE(l.paths.empty());
  EXPECT_GT(l.paths.front().duration(), 0.0f);
}

TEST(LevelFiles, NamesResolveUnderContentDirAndEnvOverride) {
  EXPECT_EQ(resolve_level_path("cornell_lights"),
            std::filesystem::path(LANTERN_TEST_CONTENT_DIR) / "levels" / "cornell_lights.json");
  ::setenv("LANTERN_CONTENT_DIR", test::data_dir().c_str(), 1);
  const std::string message = test::input_error_of([] { resolve_level_path("cornell_lights"); });
  ::unsetenv("LANTERN_CONTENT_DIR");
  EXPECT_NE(message.find("cornell_lights"), std::string::npos);
  EXPECT_NE(message.find((test::data_dir() / "levels").string()), std::string::npos);
}

}  // namespace
}  // namespace lantern
