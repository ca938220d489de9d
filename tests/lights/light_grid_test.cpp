// Light grid: every placed light sits in exactly one cell, in its place's cell, with that cell's
// count in its record; a directional light is in none; draws near a point follow
// light_grid_pdf exactly (the shaders' draw: shared/light_grid.h's neighbour and pick, then the
// table's two reads); the cell edge follows the lights' density and the axes' limit.
#include "lighting/lights/light_grid.h"

#include <gtest/gtest.h>

#include <map>
#include <random>
#include <vector>

#include "shared/light_grid.h"

namespace lantern {
namespace {

using gpu::GpuLight;
using gpu::uintBitsToFloat;

GpuLight point_light(gpu::vec3 p) {
  GpuLight l{};
  l.p0 = {p, uintBitsToFloat(gpu::kLightPoint)};
  l.radiance = {1, 1, 1, 0};
  return l;
}

GpuLight triangle_light(gpu::vec3 v0, gpu::vec3 e1, gpu::vec3 e2) {
  GpuLight l{};
  l.p0 = {v0, uintBitsToFloat(gpu::kLightTriangle)};
  l.p1 = {e1, 0};
  l.p2 = {e2, 0};
  l.radiance = {1, 1, 1, 0};
  return l;
}

GpuLight directional_light() {
  GpuLight l{};
  l.p0 = {0, 0, 0, uintBitsToFloat(gpu::kLightDirectional)};
  l.p1 = {0, -1, 0, 0};
  return l;
}

// Clusters of small triangles (lanterns) and points along a street, plus one directional light.
std::vector<GpuLight> street_lights(std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<GpuLight> lights;
  for (int cluster = 0; cluster < 40; ++cluster) {
    const gpu::vec3 centre(60.0f * u(rng), 2.0f + u(rng), 20.0f * u(rng));
    for (int t = 0; t < 20; ++t) {
      const gpu::vec3 v0 = centre + 0.1f * gpu::vec3(u(rng), u(rng), u(rng));
      lights.push_back(triangle_light(v0, {0.05f, 0, 0}, {0, 0.05f, 0.01f}));
    }
    lights.push_back(point_light(centre + gpu::vec3(0.0f, -0.2f, 0.0f)));
  }
  lights.push_back(directional_light());
  return lights;
}

TEST(LightGrid, EveryPlacedLightIsInItsPlacesCellOnce) {
  const std::vector<GpuLight> lights = street_lights(1);
  const lighting::LightGrid grid(lights);
  const gpu::GpuLightGrid& h = grid.header();
  ASSERT_GT(h.origin_cell.w, 0.0f);
  ASSERT_EQ(grid.light_cells().size(), lights.size());
  EXPECT_EQ(h.dims.w, lights.size() - 1);  // all but the directional light
  EXPECT_EQ(grid.cell_count(), std::size_t{h.dims.x} * h.dims.y * h.dims.z);
  EXPECT_EQ(grid.gpu_words().size(), 8 + 2 * grid.cell_count() + h.dims.w);

  std::vector<int> seen(lights.size(), 0);
  std::uint32_t total = 0;
  std::uint32_t occupied = 0;
  for (std::uint32_t c = 0; c < grid.cell_count(); ++c) {
    const gpu::GpuLightGridCell cell = grid.cell(c);
    total += cell.count;
    if (cell.count > 0) ++occupied;
    for (std::uint32_t k = cell.first; k < cell.first + cell.count; ++k) {
      const std::uint32_t light = grid.cell_light(k);
      ++seen[light];
      gpu::vec3 place;
      ASSERT_TRUE(lighting::light_grid_place(lights[light], place));
      const gpu::uvec4 own = gpu::light_grid_cell(h, place);
      EXPECT_EQ(gpu::light_grid_index(h, own), c) << "light " << light;
      EXPECT_EQ(grid.light_cells()[light].x, gpu::light_grid_key(own));
      EXPECT_EQ(grid.light_cells()[light].y, cell.count);
    }
  }
  EXPECT_EQ(total, h.dims.w);
  EXPECT_EQ(occupied, grid.occupied_cells());
  for (std::size_t i = 0; i + 1 < lights.size(); ++i) EXPECT_EQ(seen[i], 1) << "light " << i;
  EXPECT_EQ(seen.back(), 0);
  EXPECT_EQ(grid.light_cells().back().x, gpu::kLightGridNoCell);
  // Neither a directional light nor a light outside the neighbourhood has a density there.
  EXPECT_EQ(gpu::light_grid_pdf(grid.light_cells().back(), gpu::uvec4(0u)), 0.0f);
}

// The shaders' draw (lib/scene_buffers.glsl's scene_light_grid_draw) over the CPU arrays.
std::uint32_t draw(const lighting::LightGrid& grid, gpu::uvec4 cell, float u_cell, float u_light) {
  gpu::uvec4 neighbour;
  if (!gpu::light_grid_neighbour(grid.header(), cell, u_cell, neighbour)) {
    return gpu::kInvalidLight;
  }
  const gpu::GpuLightGridCell c = grid.cell(gpu::light_grid_index(grid.header(), neighbour));
  if (c.count == 0) return gpu::kInvalidLight;
  return grid.cell_light(c.first + gpu::light_grid_pick(c.count, u_light));
}

TEST(LightGrid, DrawsNearAPointFollowTheDensity) {
  const std::vector<GpuLight> lights = street_lights(2);
  const lighting::LightGrid grid(lights);
  // Stratified: one u_cell per 27th, then one u_light per light of the cell it picks, so every
  // (cell, light) pair is drawn once with the weight its strata have.
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (int point = 0; point < 12; ++point) {
    // Points beside the lights (where the draws matter) and a few anywhere.
    gpu::vec3 x;
    if (point < 8) {
      lighting::light_grid_place(lights[(point * 83) % (lights.size() - 1)], x);
      x += gpu::vec3(0.3f * u(rng), -0.2f, 0.1f);
    } else {
      x = gpu::vec3(70.0f * u(rng) - 5.0f, 4.0f * u(rng), 25.0f * u(rng) - 2.0f);
    }
    const gpu::uvec4 cell = gpu::light_grid_cell(grid.header(), x);
    std::map<std::uint32_t, double> frequency;
    double nothing = 0.0;
    for (std::uint32_t a = 0; a < gpu::kLightGridNeighbourCells; ++a) {
      const float u_cell = (a + 0.5f) / float(gpu::kLightGridNeighbourCells);
      gpu::uvec4 neighbour;
      std::uint32_t count = 0;
      if (gpu::light_grid_neighbour(grid.header(), cell, u_cell, neighbour)) {
        count = grid.cell(gpu::light_grid_index(grid.header(), neighbour)).count;
      }
      if (count == 0) {
        EXPECT_EQ(draw(grid, cell, u_cell, 0.5f), gpu::kInvalidLight);
        nothing += 1.0 / gpu::kLightGridNeighbourCells;
        continue;
      }
      for (std::uint32_t b = 0; b < count; ++b) {
        const std::uint32_t l = draw(grid, cell, u_cell, (b + 0.5f) / float(count));
        frequency[l] += 1.0 / (double(gpu::kLightGridNeighbourCells) * count);
      }
    }
    double pdf_sum = 0.0;
    for (std::uint32_t l = 0; l < lights.size(); ++l) {
      const double pdf = gpu::light_grid_pdf(grid.light_cells()[l], cell);
      pdf_sum += pdf;
      const auto it = frequency.find(l);
      const double f = it == frequency.end() ? 0.0 : it->second;
      EXPECT_NEAR(f, pdf, 1e-9 + 1e-6 * pdf) << "point " << point << " light " << l;
    }
    EXPECT_NEAR(pdf_sum + nothing, 1.0, 1e-6) << "point " << point;  // float densities
    if (point < 8) {
      EXPECT_GT(pdf_sum, 0.0) << "a point beside a light must reach it";
    }
  }
}

TEST(LightGrid, CellEdgeFollowsTheLightsDensity) {
  // 4096 points on a 16^3 lattice 1 m apart: about kTargetLightsPerCell per occupied cell.
  std::vector<GpuLight> lights;
  for (int z = 0; z < 16; ++z)
    for (int y = 0; y < 16; ++y)
      for (int x = 0; x < 16; ++x) lights.push_back(point_light(gpu::vec3(x, y, z)));
  const lighting::LightGrid grid(lights);
  const double mean = double(grid.header().dims.w) / double(grid.occupied_cells());
  EXPECT_GT(mean, lighting::LightGrid::kTargetLightsPerCell / 1.5 / 1.5 / 1.5);
  EXPECT_LT(mean, lighting::LightGrid::kTargetLightsPerCell * 1.5 * 1.5 * 1.5);
  // Two far clusters: the axes' 1024 cells bound the edge from below.
  const std::vector<GpuLight> two = {point_light(gpu::vec3(0.0f)), point_light({1e4f, 0, 0})};
  const lighting::LightGrid far(two);
  EXPECT_LE(far.header().dims.x, gpu::kLightGridAxisCells);
  EXPECT_GE(far.header().origin_cell.w, 1e4f / float(gpu::kLightGridAxisCells));
  // Places too far apart for a float box (the extent overflows): no grid, rather than a guess.
  const std::vector<GpuLight> apart = {point_light({-3e38f, 0, 0}), point_light({3e38f, 0, 0})};
  const lighting::LightGrid overflow(apart);
  EXPECT_EQ(overflow.header().origin_cell.w, 0.0f);
  EXPECT_EQ(overflow.light_cells()[1].x, gpu::kLightGridNoCell);
  // No placed light: no grid, nothing ever drawn.
  const std::vector<GpuLight> sun = {directional_light()};
  const lighting::LightGrid none(sun);
  EXPECT_EQ(none.header().origin_cell.w, 0.0f);
  EXPECT_EQ(none.light_cells()[0].x, gpu::kLightGridNoCell);
}

}  // namespace
}  // namespace lantern
