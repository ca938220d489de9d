// Light table: stable ids survive reordering, removal and addition; the prev<->cur maps are
// inverse where both exist; the alias table is rebuilt only when power changes; a frame of lights
// that only moved or flickered is read range by range.
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

// update_ranges: a frame whose lights only moved or flickered re-reads just the ranges it is
// given (what lies outside them is not read: the table keeps its own copy), keeps every index,
// and matches a full update of the same list; a changed id in a range falls back to update().
TEST(LightTable, UpdateRangesReadsOnlyTheChangedLights) {
  std::vector<LightEmitter> lights = {emitter(1, 1), emitter(2, 2), emitter(3, 3), emitter(4, 4)};
  LightTable ranged;
  LightTable full;
  ranged.update(lights);
  full.update(lights);

  lights[2].power = 6.0f;       // flicker
  lights[3].light.p0.y = 9.0f;  // moved
  std::vector<LightEmitter> given = lights;
  given[0].light.p0.y = -1.0f;  // outside the ranges: must not be read
  const lantern::lighting::LightRange changed[] = {{2, 2}};
  EXPECT_TRUE(ranged.update_ranges(given, changed));
  EXPECT_TRUE(full.update(lights));
  ASSERT_EQ(ranged.lights().size(), 4u);
  EXPECT_EQ(ranged.lights()[0].p0.y, 0.0f);
  EXPECT_EQ(ranged.lights()[3].p0.y, 9.0f);
  for (std::uint32_t i = 0; i < 4; ++i) {
    EXPECT_EQ(ranged.previous_to_current()[i], i);
    EXPECT_EQ(ranged.current_to_previous()[i], i);
    EXPECT_EQ(ranged.alias_table().pdf(i), full.alias_table().pdf(i)) << i;
  }
  EXPECT_NEAR(ranged.alias_table().pdf(2), 6.0f / 13.0f, 1e-6f);

  // Moved only: no rebuild.
  lights[1].light.p0.y = 3.0f;
  const lantern::lighting::LightRange moved[] = {{1, 1}};
  EXPECT_FALSE(ranged.update_ranges(lights, moved));
  EXPECT_EQ(ranged.lights()[1].p0.y, 3.0f);
  EXPECT_EQ(ranged.alias_rebuilds(), 2u);

  // Light 2 replaced by light 5 of the same power inside the range: a full update with the
  // remap (no rebuild: the powers are the same).
  lights[1] = emitter(5, 2);
  EXPECT_FALSE(ranged.update_ranges(lights, moved));
  EXPECT_EQ(ranged.previous_to_current()[1], kInvalidLight);
  EXPECT_EQ(ranged.current_to_previous()[1], kInvalidLight);
  EXPECT_EQ(ranged.stable_ids()[1], 5u);
}
