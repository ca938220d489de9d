// The light spread (lighting/scene/light_spread.h), on the CPU: 0 for one light, the closed form
// for two, unchanged when emitting panels are subdivided, and on the side of ReSTIR's local-list
// threshold that the shipped levels were measured on.
#include "lighting/scene/light_spread.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <glm/glm.hpp>
#include <string>

#include "engine/level/level_loader.h"
#include "engine/level/primitives.h"
#include "lighting/restir/restir_integrator.h"
#include "lighting/scene/scene_data.h"

namespace lantern::lighting {
namespace {

// A dark plane of side `size` at the origin facing +Y, lit by point lights of intensity 1 at
// the heights given.
Level plane_under_bulbs(float size, std::initializer_list<float> heights) {
  Level level;
  level.meshes.push_back(make_plane(glm::vec2(size, size)));
  level.materials.push_back(Material{});
  level.instances.push_back(Instance{});
  for (float h : heights) {
    Light bulb;
    bulb.position = glm::vec3(0.0f, h, 0.0f);
    level.lights.push_back(bulb);
  }
  return level;
}

TEST(LightSpread, OneLightHasNone) {
  const SceneData scene = build_scene_data(plane_under_bulbs(4.0f, {2.0f}));
  EXPECT_EQ(scene.light_spread.points, 256u);
  EXPECT_LT(scene.light_spread.spread, 1e-5f);
}

// Two equal bulbs straight above a point, at distances 1 and 2: each drawn with probability 1/2,
// contributions c1 = 1 and c2 = 1/4, so w = c / p is 2 or 1/2 and its relative variance is
// (c1 - c2)^2 / (c1 + c2)^2 = 0.36.
TEST(LightSpread, TwoBulbsMatchTheClosedForm) {
  const SceneData scene = build_scene_data(plane_under_bulbs(1e-3f, {1.0f, 2.0f}));
  const LightSpread spread = measure_light_spread(scene, 4, 200000);
  EXPECT_EQ(spread.points, 4u);
  EXPECT_NEAR(spread.spread, 0.36f, 0.01f);
  EXPECT_LT(scene.light_spread.spread, 0.5f);  // the default estimate: 256 draws
}

TEST(LightSpread, NoLightsHaveNone) {
  const LightSpread dark = build_scene_data(plane_under_bulbs(4.0f, {})).light_spread;
  EXPECT_EQ(dark.spread, 0.0f);
  EXPECT_EQ(dark.points, 0u);
}

Level panels_with(int emitters) {
  const std::filesystem::path file =
      std::filesystem::temp_directory_path() /
      ("lantern_light_spread_panels_" + std::to_string(emitters) + ".json");
  std::ofstream(file) << R"({"generators": [{"type": "light_panels", "seed": 12, )"
                      << R"("emitter_triangles": )" << emitters << "}]}";
  Level level = load_level(file);
  std::filesystem::remove(file);
  return level;
}

// light_panels (goal 3's scaling level) subdivides the same panels into more triangles: the light
// a surface receives is the same, so is the spread, and it stays below the local lists'
// threshold; night_market's lanterns each light their stall, well above it.
TEST(LightSpread, SubdividedPanelsKeepTheirSpreadAndLanternsHaveMore) {
  const float coarse = build_scene_data(panels_with(1000)).light_spread.spread;
  const float fine = build_scene_data(panels_with(100000)).light_spread.spread;
  EXPECT_GT(coarse, 1.0f);
  EXPECT_NEAR(fine, coarse, 0.15f * coarse);
  EXPECT_LT(2.0f * fine, RestirIntegrator::kLocalListsMinSpread);
  const float market = build_scene_data(load_level_argument("night_market")).light_spread.spread;
  EXPECT_GT(market, 2.0f * RestirIntegrator::kLocalListsMinSpread);
}

}  // namespace
}  // namespace lantern::lighting
