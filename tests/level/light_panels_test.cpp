// The light_panels generator (goal 3's scaling level): every emitter count is exact, carries the
// same total emitted power over the same emitting surface, and leaves the rest of the level
// (occluders, floor, camera path) bit-identical; a count the panels cannot split is one named
// error.
#include "engine/level/generators/light_panels.h"

#include <gtest/gtest.h>

#include <glm/glm.hpp>
#include <string>

#include "engine/core/error.h"
#include "engine/level/level_loader.h"
#include "engine/scene/level_summary.h"
#include "tests/level/test_files.h"

namespace lantern {
namespace {

Level panels_with(int triangles) {
  const auto file = test::scratch("panels_" + std::to_string(triangles) + ".json");
  test::write_text(file,
                   R"({"generators": [{"type": "light_panels", "seed": 4, "emitter_triangles": )" +
                       std::to_string(triangles) + "}]}");
  return load_level(file);
}

// Sum over emissive triangles of area x radiance (rgb): the emitted power / pi, per channel.
glm::dvec3 emitted_power(const Level& level, double* area = nullptr) {
  glm::dvec3 power(0.0);
  double total_area = 0.0;
  for (const Instance& inst : level.instances) {
    const Material& m = level.materials[inst.material];
    const glm::dvec3 radiance = glm::dvec3(m.emissive_factor) * double(m.emissive_strength);
    if (radiance == glm::dvec3(0.0)) continue;
    const Mesh& mesh = level.meshes[inst.mesh];
    for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
      const glm::dvec3 a(inst.world * glm::vec4(mesh.positions[mesh.indices[3 * t]], 1.0f));
      const glm::dvec3 b(inst.world * glm::vec4(mesh.positions[mesh.indices[3 * t + 1]], 1.0f));
      const glm::dvec3 c(inst.world * glm::vec4(mesh.positions[mesh.indices[3 * t + 2]], 1.0f));
      const double tri_area = 0.5 * glm::length(glm::cross(b - a, c - a));
      power += tri_area * radiance;
      total_area += tri_area;
    }
  }
  if (area) *area = total_area;
  return power;
}

TEST(LightPanels, EveryCountIsExactWithTheSamePowerAndTheSameOccluders) {
  const Level small = panels_with(1000);
  double small_area = 0.0;
  const glm::dvec3 small_power = emitted_power(small, &small_area);
  const LevelSummary small_summary = summarize(small);
  EXPECT_EQ(small_summary.emissive_triangles, 1000u);
  for (int n : {10000, 100000}) {
    const Level big = panels_with(n);
    const LevelSummary s = summarize(big);
    EXPECT_EQ(s.emissive_triangles, static_cast<std::size_t>(n));
    // Non-emitting geometry is unchanged.
    EXPECT_EQ(s.triangles - s.emissive_triangles,
              small_summary.triangles - small_summary.emissive_triangles);
    double area = 0.0;
    const glm::dvec3 power = emitted_power(big, &area);
    EXPECT_NEAR(area, small_area, 1e-4 * small_area) << n;
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(power[k], small_power[k], 1e-4 * small_power[k]) << n;
    // Occluders and floor: the same meshes at the same places.
    ASSERT_EQ(big.instances.size(), small.instances.size());
    for (std::size_t i = 0; i < big.instances.size(); ++i) {
      const Material& m = big.materials[big.instances[i].material];
      if (m.emissive_factor != glm::vec3(0.0f)) continue;  // a panel
      EXPECT_EQ(big.meshes[big.instances[i].mesh].positions,
                small.meshes[small.instances[i].mesh].positions);
      EXPECT_EQ(big.instances[i].world, small.instances[i].world);
    }
  }
}

TEST(LightPanels, ShippedLevelLoadsWithItsPath) {
  const Level level = load_level_argument("light_panels");
  EXPECT_EQ(summarize(level).emissive_triangles, 1000u);
  ASSERT_NE(level.find_path(level.camera_path), nullptr);
  EXPECT_EQ(level.find_path(level.camera_path)->problem(), "");
}

TEST(LightPanels, GridCellsAreAsSquareAsTheCountAllows) {
  EXPECT_EQ(light_panel_grid(25000, {2.4f, 1.2f}), glm::uvec2(200, 125));
  EXPECT_EQ(light_panel_grid(50, {2.4f, 1.2f}), glm::uvec2(10, 5));
  EXPECT_EQ(light_panel_grid(7, {2.4f, 1.2f}), glm::uvec2(7, 1));  // a prime: one row
}

TEST(LightPanels, ACountThePanelsCannotSplitIsNamed) {
  const auto file = test::scratch("panels_bad.json");
  test::write_text(file,
                   R"({"generators": [{"type": "light_panels", "emitter_triangles": 1001}]})");
  try {
    load_level(file);
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("emitter_triangles"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace lantern
