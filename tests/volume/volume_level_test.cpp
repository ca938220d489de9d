// Volumes in levels: the shipped volume levels load and summarise with their grids; a
// zero-density volume is fine; a level without volumes reads no grid and reports no volume
// passes; volume entities carry their placement and behaviour into the ECS.
#include <gtest/gtest.h>

#include <cstdlib>

#include "engine/ecs/registry.h"
#include "engine/level/level_loader.h"
#include "engine/scene/level_summary.h"
#include "engine/world/components.h"
#include "engine/world/instantiate.h"
#include "engine/world/world.h"
#include "lighting/scene/scene_requirements.h"
#include "runtime/volume/volume_set.h"
#include "tests/volume/vdb_fixtures.h"

namespace lantern::test {
namespace {

class VolumeLevel : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    setenv("LANTERN_CACHE_DIR", volume_scratch("level_cache").c_str(), 1);
  }
  static LevelSummary describe(const Level& level) {
    LevelSummary s = summarize(level);
    lighting::describe_requirements(level, 64, 36, s);
    return s;
  }
};

TEST_F(VolumeLevel, WithoutVolumesNoGridIsReadAndNoVolumePassRuns) {
  const std::uint64_t before = runtime::volume_grids_read();
  const LevelSummary s = describe(load_level_argument("cornell_lights"));
  EXPECT_EQ(s.volumes, 0u);
  EXPECT_EQ(s.enabled.at("volumes").at("passes"), "volume passes: none");
  EXPECT_EQ(s.enabled.at("volumes").at("bytes"), 0);
  EXPECT_EQ(runtime::volume_grids_read(), before);
  EXPECT_TRUE(runtime::load_volume_grids(load_level_argument("cornell_lights")).empty());
  EXPECT_EQ(runtime::volume_grids_read(), before);
}

TEST_F(VolumeLevel, FogBoxLoadsAndSummarises) {
  const Level level = load_level_argument("fog_box");
  ASSERT_EQ(level.volumes.size(), 1u);
  const LevelSummary s = describe(level);
  EXPECT_EQ(s.volumes, 1u);
  const nlohmann::json& grids = s.enabled.at("volumes").at("grids");
  ASSERT_EQ(grids.size(), 1u);
  EXPECT_EQ(grids[0].at("active_voxels"), 32u * 20u * 32u);
  EXPECT_EQ(grids[0].at("grid"), "density");
  EXPECT_GT(s.enabled.at("volumes").at("bytes").get<std::uint64_t>(), 32u * 20u * 32u * 4u);
  EXPECT_NE(to_text(s).find("volume passes"), std::string::npos);
}

TEST_F(VolumeLevel, SmokeYardHasTwoMovingAndStillGrids) {
  const Level level = load_level_argument("smoke_yard");
  const LevelSummary s = describe(level);
  ASSERT_EQ(s.enabled.at("volumes").at("grids").size(), 2u);
  for (const nlohmann::json& g : s.enabled.at("volumes").at("grids")) {
    EXPECT_GT(g.at("active_voxels").get<std::uint64_t>(), 1000u);
    EXPECT_LE(g.at("active_voxels").get<std::uint64_t>(), 70000u);  // small: generated at load
  }
}

TEST_F(VolumeLevel, ZeroDensityVolumeLoadsAndSummarises) {
  const auto file = volume_scratch("zero_density.json");
  write_text_file(file, R"({"primitives": [{"type": "plane"}],
    "volumes": [{"generate": {"type": "constant", "size": [1, 1, 1], "voxel_size": 0.25},
                 "density_scale": 0}]})");
  const Level level = load_level(file);
  const LevelSummary s = describe(level);
  EXPECT_EQ(s.volumes, 1u);
  EXPECT_EQ(s.enabled.at("volumes").at("grids")[0].at("active_voxels"), 64u);
  // A grid whose active values are all zero stores no brick at all.
  const auto vdb = volume_scratch("zeros.vdb");
  write_vdb(vdb, {cube_grid("density", 4, 0.0f)});
  Volume v;
  v.file = vdb;
  v.where = "zeros";
  const runtime::VolumeGrid g = runtime::load_volume_grid(v);
  EXPECT_EQ(g.brick_count(), 0u);
  EXPECT_EQ(g.sample(glm::vec3(1.5f)), 0.0f);
}

TEST_F(VolumeLevel, VolumesBecomeEntitiesThatMove) {
  const auto level = std::make_shared<const Level>(load_level_argument("smoke_yard"));
  Registry registry;
  const WorldEntities made = instantiate(registry, level);
  EXPECT_EQ(made.volumes, 2u);
  std::size_t volumes = 0, moving = 0;
  registry.view<const VolumeComponent, const StableId>().each(
      [&](const VolumeComponent& v, const StableId& id) {
        EXPECT_EQ(id.kind, EntityKind::Volume);
        EXPECT_EQ(id.value, v.index);
        ++volumes;
      });
  registry.view<const VolumeComponent, const DynamicTransform, const OrbitComponent>().each(
      [&](const VolumeComponent& v, const DynamicTransform&, const OrbitComponent&) {
        EXPECT_EQ(level->volumes[v.index].name, "plume");
        ++moving;
      });
  EXPECT_EQ(volumes, 2u);
  EXPECT_EQ(moving, 1u);
}

// The Extract phase copies each volume's placement (and last frame's) into the snapshot: the
// circling plume moves, the fog bank stays; a level without volumes has none.
TEST_F(VolumeLevel, SnapshotsCarryVolumePlacements) {
  World world(std::make_shared<const Level>(load_level_argument("smoke_yard")), {.threads = 2});
  const FrameSnapshot first = world.step();
  ASSERT_EQ(first.volumes.size(), 2u);
  EXPECT_EQ(first.volumes[0].stable_id, 0u);
  EXPECT_EQ(first.volumes[1].stable_id, 1u);
  EXPECT_EQ(first.volumes[1].prev_object_to_world, first.volumes[1].object_to_world);
  const FrameSnapshot second = world.step();
  EXPECT_EQ(second.volumes[0].object_to_world, first.volumes[0].object_to_world);  // fog: still
  EXPECT_NE(second.volumes[1].object_to_world, first.volumes[1].object_to_world);  // plume moves
  EXPECT_EQ(second.volumes[1].prev_object_to_world, first.volumes[1].object_to_world);
  EXPECT_EQ(frozen(second).volumes[1].prev_object_to_world, second.volumes[1].object_to_world);

  World plain(std::make_shared<const Level>(load_level_argument("cornell_lights")), {});
  EXPECT_TRUE(plain.step().volumes.empty());
}

}  // namespace
}  // namespace lantern::test
