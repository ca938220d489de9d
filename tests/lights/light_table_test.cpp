// Light table: stable ids survive reordering, removal and addition; the prev<->cur maps are
// inverse where both exist; the alias table is rebuilt only when power changes; a frame of lights
// that only moved or flickered is read range by range.
#include "lighting/lights/light_table.h"

#include <gtest/gtest.h>

#include <limits>

#include "engine/core/error.h"

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
  table.update(frame0, 0);
  EXPECT_EQ(table.previous_to_current().size(), 0u);
  for (auto prev : table.current_to_previous()) EXPECT_EQ(prev, kInvalidLight);

  // Light 11 removed, 14 added, the rest reordered.
  std::vector<LightEmitter> frame1 = {emitter(13, 4), emitter(14, 5), emitter(10, 1), emitter(12, 3)};
  table.update(frame1, 0);
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
  table.update({}, 0);
  for (auto cur : table.previous_to_current()) EXPECT_EQ(cur, kInvalidLight);
  EXPECT_FALSE(table.has_power());
}

TEST(LightTable, AliasRebuiltOnlyWhenPowerChanges) {
  LightTable table;
  std::vector<LightEmitter> lights = {emitter(1, 1), emitter(2, 3)};
  EXPECT_TRUE(table.update(lights, 0));
  const std::uint64_t built = table.alias_rebuilds();
  lights[0].light.p0.y = 5.0f;  // moved, same power
  EXPECT_FALSE(table.update(lights, 0));
  EXPECT_EQ(table.alias_rebuilds(), built);
  lights[1].power = 4.0f;  // flicker
  EXPECT_TRUE(table.update(lights, 0));
  EXPECT_NEAR(table.selection_pdf(1), 0.8f, 1e-6f);
}

TEST(LightTable, ZeroPowerLightsLeaveNoSamplingTable) {
  LightTable table;
  std::vector<LightEmitter> dark = {emitter(1, 0), emitter(2, 0)};
  table.update(dark, 0);
  EXPECT_EQ(table.lights().size(), 2u);
  EXPECT_FALSE(table.has_power());
}

TEST(LightTable, DuplicateIdsAreRejected) {
  LightTable table;
  std::vector<LightEmitter> lights = {emitter(7, 1), emitter(7, 2)};
  EXPECT_THROW(table.update(lights, 0), lantern::InputError);
}

// update_ranges: a frame whose lights only moved or flickered re-reads just the ranges it is
// given (what lies outside them is not read: the table keeps its own copy), keeps every index,
// and matches a full update of the same list; a changed id in a range falls back to update().
TEST(LightTable, UpdateRangesReadsOnlyTheChangedLights) {
  std::vector<LightEmitter> lights = {emitter(1, 1), emitter(2, 2), emitter(3, 3), emitter(4, 4)};
  LightTable ranged;
  LightTable full;
  ranged.update(lights, 0);
  full.update(lights, 0);

  lights[2].power = 6.0f;       // flicker
  lights[3].light.p0.y = 9.0f;  // moved
  std::vector<LightEmitter> given = lights;
  given[0].light.p0.y = -1.0f;  // outside the ranges: must not be read
  const lantern::lighting::LightRange changed[] = {{2, 2}};
  EXPECT_TRUE(ranged.update_ranges(given, changed));
  EXPECT_TRUE(full.update(lights, 0));
  ASSERT_EQ(ranged.lights().size(), 4u);
  EXPECT_EQ(ranged.lights()[0].p0.y, 0.0f);
  EXPECT_EQ(ranged.lights()[3].p0.y, 9.0f);
  for (std::uint32_t i = 0; i < 4; ++i) {
    EXPECT_EQ(ranged.previous_to_current()[i], i);
    EXPECT_EQ(ranged.current_to_previous()[i], i);
    EXPECT_EQ(ranged.selection_pdf(i), full.selection_pdf(i)) << i;
  }
  EXPECT_NEAR(ranged.selection_pdf(2), 6.0f / 13.0f, 1e-6f);

  // Moved only: no rebuild.
  lights[1].light.p0.y = 3.0f;
  const lantern::lighting::LightRange moved[] = {{1, 1}};
  const std::uint64_t built = ranged.alias_rebuilds();
  EXPECT_FALSE(ranged.update_ranges(lights, moved));
  EXPECT_EQ(ranged.lights()[1].p0.y, 3.0f);
  EXPECT_EQ(ranged.alias_rebuilds(), built);

  // Light 2 replaced by light 5 of the same power inside the range: a full update with the
  // remap (no rebuild: the powers are the same).
  lights[1] = emitter(5, 2);
  EXPECT_FALSE(ranged.update_ranges(lights, moved));
  EXPECT_EQ(ranged.previous_to_current()[1], kInvalidLight);
  EXPECT_EQ(ranged.current_to_previous()[1], kInvalidLight);
  EXPECT_EQ(ranged.stable_ids()[1], 5u);
}

// The probability that LightTable::sample draws each light, from its two alias tables' entries
// and the first group's share (what the GPU's scene_light_sample does), enumerated exactly.
std::vector<double> implied_probabilities(const LightTable& table) {
  const auto& entries = table.alias_entries();
  const std::size_t split = table.first_group_size();
  std::vector<double> p(entries.size(), 0.0);
  for (std::size_t slot = 0; slot < entries.size(); ++slot) {
    const bool first = slot < split;
    const double group = first ? table.first_group_share() : 1.0 - table.first_group_share();
    const double per_slot = group / double(first ? split : entries.size() - split);
    p[slot] += per_slot * entries[slot].threshold;
    p[entries[slot].alias] += per_slot * (1.0 - entries[slot].threshold);
  }
  return p;
}

std::vector<LightEmitter> grouped(std::vector<float> powers) {
  std::vector<LightEmitter> lights;
  for (std::size_t i = 0; i < powers.size(); ++i) lights.push_back(emitter(100 + i, powers[i]));
  return lights;
}

// Two groups (three "triangles", then two "analytic" lights): each light is drawn in proportion
// to its power over all of them, and selection_pdf says so, as one table over all would.
TEST(LightTable, TwoGroupsDrawEachLightInProportionToItsPower) {
  const std::vector<float> powers = {1.0f, 4.0f, 0.0f, 2.5f, 0.5f};
  LightTable table;
  table.update(grouped(powers), 3);
  EXPECT_EQ(table.first_group_size(), 3u);
  EXPECT_NEAR(table.first_group_share(), 5.0f / 8.0f, 1e-7f);
  EXPECT_DOUBLE_EQ(table.total_power(), 8.0);
  const std::vector<double> implied = implied_probabilities(table);
  for (std::uint32_t i = 0; i < powers.size(); ++i) {
    EXPECT_NEAR(implied[i], powers[i] / 8.0, 1e-6) << i;
    EXPECT_NEAR(table.selection_pdf(i), powers[i] / 8.0, 1e-6) << i;
  }
  // A draw below the share lands in the first group, above it in the second.
  EXPECT_LT(table.sample(0.6f, 0.5f), 3u);
  EXPECT_GE(table.sample(0.63f, 0.5f), 3u);
  EXPECT_LT(table.sample(0.99999994f, 0.99999994f), 5u);
  EXPECT_LT(table.sample(0.0f, 0.0f), 3u);
}

// Analytic lights that flicker rebuild only their own table: the triangles' entries are not
// rewritten (nor uploaded again: alias_rewritten), and the draw stays proportional to power.
TEST(LightTable, FlickerRebuildsOnlyItsGroupsTable) {
  std::vector<LightEmitter> lights = grouped({1.0f, 4.0f, 3.0f, 2.5f, 0.5f});
  LightTable table;
  table.update(lights, 3);
  const std::vector<lantern::gpu::AliasEntry> before = table.alias_entries();
  const std::uint64_t built = table.alias_rebuilds();

  lights[4].power = 1.5f;
  const lantern::lighting::LightRange analytic[] = {{3, 2}};
  EXPECT_TRUE(table.update_ranges(lights, analytic));
  EXPECT_EQ(table.alias_rebuilds(), built + 1);
  EXPECT_EQ(table.alias_rewritten().first, 3u);
  EXPECT_EQ(table.alias_rewritten().count, 2u);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(table.alias_entries()[i].threshold, before[i].threshold) << i;
    EXPECT_EQ(table.alias_entries()[i].alias, before[i].alias) << i;
  }
  const std::vector<double> implied = implied_probabilities(table);
  for (std::uint32_t i = 0; i < lights.size(); ++i)
    EXPECT_NEAR(implied[i], lights[i].power / 12.0, 1e-6) << i;

  // A triangle's power changes: its group's entries are rewritten, the analytic ones are not.
  lights[0].power = 2.0f;
  const lantern::lighting::LightRange triangle[] = {{0, 1}};
  EXPECT_TRUE(table.update_ranges(lights, triangle));
  EXPECT_EQ(table.alias_rewritten().first, 0u);
  EXPECT_EQ(table.alias_rewritten().count, 3u);
  EXPECT_NEAR(table.selection_pdf(0), 2.0f / 13.0f, 1e-6f);
  EXPECT_NEAR(table.selection_pdf(4), 1.5f / 13.0f, 1e-6f);

  // Nothing changed power: nothing rewritten.
  lights[1].light.p0.y = 7.0f;
  const lantern::lighting::LightRange moved[] = {{1, 1}};
  EXPECT_FALSE(table.update_ranges(lights, moved));
  EXPECT_EQ(table.alias_rewritten().count, 0u);
}

// A group without power is never drawn (its share is exactly 0, or the other's exactly 1), and a
// group with power is drawn however small its share: the share stays a float step inside (0, 1)
// so the draw can land in it, and its lights' pdf matches how often it does.
TEST(LightTable, GroupSharesAtTheExtremes) {
  LightTable table;
  table.update(grouped({0.0f, 0.0f, 3.0f, 1.0f}), 2);
  EXPECT_EQ(table.first_group_share(), 0.0f);
  for (float u0 : {0.0f, 0.5f, 0.99999994f}) EXPECT_GE(table.sample(u0, 0.5f), 2u) << u0;
  EXPECT_NEAR(table.selection_pdf(2), 0.75f, 1e-6f);

  table.update(grouped({2.0f, 2.0f, 0.0f, 0.0f}), 2);
  EXPECT_EQ(table.first_group_share(), 1.0f);
  for (float u0 : {0.0f, 0.5f, 0.99999994f}) EXPECT_LT(table.sample(u0, 0.5f), 2u) << u0;

  table.update(grouped({1e12f, 1e12f, 1e-3f, 1e-3f}), 2);
  const float share = table.first_group_share();
  EXPECT_LT(share, 1.0f);
  EXPECT_GE(table.sample(0.99999994f, 0.5f), 2u);
  EXPECT_NEAR(table.selection_pdf(2), 0.5f * (1.0f - share), 1e-12f);
  const std::vector<double> implied = implied_probabilities(table);
  EXPECT_NEAR(implied[2], table.selection_pdf(2), 1e-12);

  table.update(grouped({0.0f, 0.0f, 0.0f}), 2);
  EXPECT_FALSE(table.has_power());
}

// Powers that move by float rounding (a rotating emitter's area: up to 1.2e-4 of itself) keep the
// table; a real change rebuilds it, and so does one that switches a light on or off; a drift in
// small steps is caught once it adds up to the tolerance (the table keeps the powers it was
// built with); a non-finite power is refused.
TEST(LightTable, RoundingDoesNotRebuildButChangeAndDriftDo) {
  std::vector<LightEmitter> lights = grouped({2.0f, 3.0f, 1.0f});
  LightTable table;
  table.update(lights, 2);
  const lantern::lighting::LightRange all[] = {{0, 3}};
  lights[0].power = 2.0f * (1.0f + 2e-4f);
  EXPECT_FALSE(table.update_ranges(lights, all));
  EXPECT_NEAR(table.selection_pdf(0), 2.0f / 6.0f, 1e-6f);  // the built power still
  for (int step = 0; step < 4; ++step) {  // +0.4% more in steps of 0.1%: caught on the way
    lights[0].power *= 1.001f;
    table.update_ranges(lights, all);
  }
  EXPECT_NEAR(table.selection_pdf(0), lights[0].power / (lights[0].power + 4.0f), 1e-3f);
  lights[2].power = 0.0f;  // switched off
  EXPECT_TRUE(table.update_ranges(lights, all));
  EXPECT_EQ(table.selection_pdf(2), 0.0f);
  lights[2].power = 1e-9f;  // switched on, however faintly
  EXPECT_TRUE(table.update_ranges(lights, all));
  EXPECT_GT(table.selection_pdf(2), 0.0f);
  lights[1].power = std::numeric_limits<float>::quiet_NaN();
  EXPECT_THROW(table.update_ranges(lights, all), lantern::InputError);
}
