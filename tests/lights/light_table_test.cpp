// Light table: stable ids survive reordering, removal and addition; the prev<->cur maps are
// inverse where both exist; the alias table is rebuilt only when power changes.
#include <gtest/gtest.h>

#include "engine/core/error.h"
#include "lighting/lights/light_table.h"

using lantern::gpu::kInvalidLight;
using lantern::lighting::LightEmitter;
using lantern::lighting::LightTable;

namespace {
LightEmitter emitter(std::uint64_t id, float power) {
  LightEmitter e;
  e.stable_id = id;
  e.power = power;
  e.light.p0 = {float(id), 0, 0, lantern::gpu::uintBitsToFloat(lantern::gpu::kLightPoint)};
  return e;
}
}  // namespace

TEST(LightTable, RemapFollowsStableIdsThroughRemovalAndAddition) {
  LightTable table;
  std::vector<LightEmitter> frame0 = {emitter(10, 1), emitter(11, 2), emitter(12, 3), emitter(13, 4)};
  table.update(frame0);
  EXPECT_EQ(table.previous_to_current().size(), 0u);
  for (auto prev : table.current_to_previous()) EXPECT_EQ(prev, kInvalidLight);

  // Light 11 removed, 14 added, the rest reordered.
  std::vector<LightEmitter> frame1 = {emitter(13, 4), emitter(14, 5), emitter(10, 1), emitter(12, 3)};
  table.update(frame1);
  const auto& p2c = table.previous_to_current();
  const auto& c2p = table.current_to_previous();
  ASSERT_EQ(p2c.size(), 4u);
  EXPECT_EQ(p2c[0], 2u);             // id 10
  EXPECT_EQ(p2c[1], kInvalidLight);  // id 11 removed
  EXPECT_EQ(p2c[2], 3u);             // id 12
  EXPECT_EQ(p2c[3], 0u);             // id 13
  ASSERT_EQ(c2p.size(), 4u);
  EXPECT_EQ(c2p[1], kInvalidLight);  // id 14 is new
  for (std::uint32_t cur = 0; cur < c2p.size(); ++cur) {
    if (c2p[cur] != kInvalidLight) {
      EXPECT_EQ(p2c[c2p[cur]], cur);
    }
  }
  EXPECT_EQ(table.lights()[2].p0.x, 10.0f);

  // All lights removed: every previous light maps to nothing, sampling has no power.
  table.update({});
  for (auto cur : table.previous_to_current()) EXPECT_EQ(cur, kInvalidLight);
  EXPECT_FALSE(table.has_power());
}

TEST(LightTable, AliasRebuiltOnlyWhenPowerChanges) {
  LightTable table;
  std::vector<LightEmitter> lights = {emitter(1, 1), emitter(2, 3)};
  EXPECT_TRUE(table.update(lights));
  lights[0].light.p0.y = 5.0f;  // moved, same power
  EXPECT_FALSE(table.update(lights));
  EXPECT_EQ(table.alias_rebuilds(), 1u);
  lights[1].power = 4.0f;  // flicker
  EXPECT_TRUE(table.update(lights));
  EXPECT_NEAR(table.alias_table().pdf(1), 0.8f, 1e-6f);
}

TEST(LightTable, ZeroPowerLightsLeaveNoSamplingTable) {
  LightTable table;
  std::vector<LightEmitter> dark = {emitter(1, 0), emitter(2, 0)};
  table.update(dark);
  EXPECT_EQ(table.lights().size(), 2u);
  EXPECT_FALSE(table.has_power());
}

TEST(LightTable, DuplicateIdsAreRejected) {
  LightTable table;
  std::vector<LightEmitter> lights = {emitter(7, 1), emitter(7, 2)};
  EXPECT_THROW(table.update(lights), lantern::InputError);
}
