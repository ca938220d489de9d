// What a level needs is what gets built: no environment tables without an environment map, no
// light-sampling structure without emitters, sizes that follow the content.
#include "lighting/scene/scene_requirements.h"

#include <gtest/gtest.h>

#include "engine/level/level_loader.h"
#include "engine/scene/level_summary.h"
#include "lighting/scene/scene_data.h"

namespace lantern::lighting {
namespace {

LevelSummary describe(const Level& level, std::uint32_t w = 64, std::uint32_t h = 36) {
  LevelSummary s = summarize(level);
  describe_requirements(level, w, h, s);
  return s;
}

TEST(SceneRequirements, EnvironmentOnlyWhenTheLevelHasOne) {
  const LevelSummary cornell = describe(load_level_argument("cornell_lights"));
  EXPECT_EQ(cornell.enabled.at("environment").at("bytes"), 0);
  const LevelSummary street = describe(load_level_argument("sunset_street"));
  EXPECT_GT(street.enabled.at("environment").at("bytes").get<std::uint64_t>(), 512u * 256u * 16u);
  EXPECT_EQ(street.enabled.at("environment").at("resolution"), "512x256");
}

TEST(SceneRequirements, LightSamplingSizedByEmitters) {
  Level dark = load_level_argument("cornell_lights");
  dark.lights.clear();
  for (Material& m : dark.materials) m.emissive_strength = 0.0f;
  const LevelSummary none = describe(dark);
  EXPECT_EQ(none.enabled.at("light_sampling").at("structure"), "none");
  EXPECT_EQ(none.enabled.at("light_sampling").at("bytes"), 0);

  const LevelSummary lit = describe(load_level_argument("cornell_lights"));
  EXPECT_EQ(lit.enabled.at("light_sampling").at("emitters"), 89);  // 88 triangles + 1 point
  EXPECT_EQ(lit.enabled.at("light_sampling").at("bytes"), 89 * (64 + 16));
  // The light spread ReSTIR's presampling and local lists follow, as the renderer measures it
  // (to 2 decimals).
  EXPECT_NEAR(lit.enabled.at("light_sampling").at("spread").get<double>(),
              build_scene_data(load_level_argument("cornell_lights")).light_spread.spread, 0.006);
  EXPECT_GT(lit.enabled.at("light_sampling").at("spread").get<float>(), 1.0f);
  // The glossiest material, which restir.bsdf_min_gloss is compared with: the box's roughness
  // 0.25 at specular 1 gives 0.375.
  EXPECT_NEAR(lit.enabled.at("geometry").at("max_gloss").get<double>(), 0.375, 1e-6);
}

TEST(SceneRequirements, PerFrameMemoryFollowsTheSize) {
  const Level level = load_level_argument("cornell_lights");
  const auto small = describe(level, 64, 36).enabled.at("per_frame").at("gbuffer_bytes").get<double>();
  const auto big = describe(level, 128, 72).enabled.at("per_frame").at("gbuffer_bytes").get<double>();
  EXPECT_DOUBLE_EQ(big, 4.0 * small);
  EXPECT_NE(to_text(describe(level)).find("enabled for this level"), std::string::npos);
}

// The text puts each section's values in one column after its longest key (a 16-character key,
// "merged_instances", ran into its value).
TEST(SceneRequirements, TextSeparatesLongKeysFromValues) {
  LevelSummary s = describe(load_level_argument("cornell_lights"));
  s.enabled["visibility"]["merged_instances"] = 48;
  s.enabled["visibility"]["a_key_longer_than_the_column"] = "x";
  const std::string text = to_text(s);
  EXPECT_NE(text.find("merged_instances"), std::string::npos);
  EXPECT_EQ(text.find("merged_instances48"), std::string::npos) << text;
  EXPECT_NE(text.find("a_key_longer_than_the_column x"), std::string::npos) << text;
  EXPECT_NE(text.find("merged_instances             48"), std::string::npos) << text;
}

}  // namespace
}  // namespace lantern::lighting
