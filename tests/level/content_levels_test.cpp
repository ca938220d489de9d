// Every level shipped under content/levels/ loads cleanly, has a flythrough path the camera
// follows or can follow, names a frame-time budget written for it, and contains what its README
// line promises.
#include <gtest/gtest.h>

#include <filesystem>

#include "engine/level/level_loader.h"
#include "engine/perf/budget.h"
#include "engine/scene/level_summary.h"

namespace lantern {
namespace {

TEST(ContentLevels, EveryLevelLoadsWithAPath) {
  int count = 0;
  for (const auto& entry :
       std::filesystem::directory_iterator(std::filesystem::path(LANTERN_TEST_CONTENT_DIR) / "levels")) {
    if (entry.path().extension() != ".json") continue;
    SCOPED_TRACE(entry.path().string());
    const Level level = load_level(entry.path());
    EXPECT_FALSE(level.paths.empty());
    EXPECT_GT(summarize(level).triangles, 0u);
    // Its budget exists, parses, and was written for this level.
    ASSERT_FALSE(level.budgets.empty());
    const perf::Budget budget = perf::load_budget(level.budgets);
    ASSERT_TRUE(budget.level.has_value());
    EXPECT_EQ(*budget.level, entry.path().stem().string());
    EXPECT_TRUE(budget.relative.has_value());
    ++count;
  }
  EXPECT_GE(count, 4);  // cornell_lights, night_market, million_lights, sunset_street
}

TEST(ContentLevels, SunsetStreetIsOutdoorWithSunEnvironmentAndMovers) {
  const Level level = load_level_argument("sunset_street");
  const LevelSummary s = summarize(level);
  EXPECT_EQ(s.directional_lights, 1u);
  ASSERT_TRUE(level.environment.has_value());
  EXPECT_TRUE(std::filesystem::exists(level.environment->path));
  std::size_t movers = 0;
  for (const Instance& i : level.instances) movers += i.behaviour.has_value();
  EXPECT_GE(movers, 8u);  // cars and pedestrians
  EXPECT_GT(s.emissive_triangles, 0u);
  EXPECT_EQ(level.camera_path, "stroll");
}

}  // namespace
}  // namespace lantern
