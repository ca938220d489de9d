// Light grid: every placed light sits in exactly one cell, in its place's cell, with its share of
// that cell's pick (half by power, half uniform) in its record and its power in the cell's sum; a directional light is in none; draws near
// a point follow light_grid_pdf exactly (the shaders' weights and draw: shared/light_grid.h's
// neighbour, weight, slot and pick over the table); the weights follow power, distance and the surface's
// side; the cell edge follows the lights' density and the axes' limit.
#include "lighting/lights/light_grid.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <map>
#include <random>
#include <stdexcept>
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

// A sampling power per light, 0.5..8 (the directional light's too: it has no place to count in).
std::vector<float> powers_of(const std::vector<GpuLight>& lights) {
  std::vector<float> powers(lights.size());
  for (std::size_t i = 0; i < lights.size(); ++i) powers[i] = 0.5f + float((i * 7) % 16) / 2.0f;
  return powers;
}

TEST(LightGrid, EveryPlacedLightIsInItsPlacesCellOnce) {
  const std::vector<GpuLight> lights = street_lights(1);
  const std::vector<float> powers = powers_of(lights);
  const lighting::LightGrid grid(lights, powers);
  const gpu::GpuLightGrid& h = grid.header();
  ASSERT_GT(h.origin_cell.w, 0.0f);
  ASSERT_EQ(grid.light_cells().size(), lights.size());
  EXPECT_EQ(h.dims.w, lights.size() - 1);  // all but the directional light
  EXPECT_EQ(grid.cell_count(), std::size_t{h.dims.x} * h.dims.y * h.dims.z);
  EXPECT_EQ(grid.gpu_words().size(), 8 + 3 * grid.cell_count() + 3 * h.dims.w);

  std::vector<int> seen(lights.size(), 0);
  std::uint32_t total = 0;
  std::uint32_t occupied = 0;
  for (std::uint32_t c = 0; c < grid.cell_count(); ++c) {
    const gpu::GpuLightGridCell cell = grid.cell(c);
    total += cell.count;
    if (cell.count > 0) ++occupied;
    double power = 0.0;
    double shares = 0.0;
    for (std::uint32_t k = cell.first; k < cell.first + cell.count; ++k) {
      const std::uint32_t light = grid.entry(k).light;
      ++seen[light];
      power += powers[light];
      shares += gpu::uintBitsToFloat(grid.light_cells()[light].y);
      gpu::vec3 place;
      ASSERT_TRUE(lighting::light_grid_place(lights[light], place));
      const gpu::uvec4 own = gpu::light_grid_cell(h, place);
      EXPECT_EQ(gpu::light_grid_index(h, own), c) << "light " << light;
      EXPECT_EQ(grid.light_cells()[light].x, gpu::light_grid_key(own));
      // Half the power pick's share, half the uniform pick's (the defensive mixture).
      EXPECT_NEAR(gpu::uintBitsToFloat(grid.light_cells()[light].y),
                  0.5 * (powers[light] / cell.power + 1.0 / cell.count), 1e-5)
          << "light " << light;
    }
    EXPECT_NEAR(cell.power, power, 1e-5 * power) << "cell " << c;
    if (cell.count > 0) {
      EXPECT_NEAR(shares, 1.0, 1e-5) << "cell " << c;
    }
  }
  EXPECT_EQ(total, h.dims.w);
  EXPECT_EQ(occupied, grid.occupied_cells());
  for (std::size_t i = 0; i + 1 < lights.size(); ++i) EXPECT_EQ(seen[i], 1) << "light " << i;
  EXPECT_EQ(seen.back(), 0);
  EXPECT_EQ(grid.light_cells().back().x, gpu::kLightGridNoCell);
  // A directional light is near no cell.
  EXPECT_EQ(gpu::light_grid_near_index(grid.light_cells().back().x, gpu::uvec4(0u)),
            gpu::kLightGridNeighbourCells);
  // One power per light, or the grid refuses to guess.
  EXPECT_THROW(lighting::LightGrid(lights, std::vector<float>(3, 1.0f)), std::invalid_argument);
}

using Weights = std::array<float, gpu::kLightGridNeighbourCells>;

// The shaders' cell weights (lib/scene_buffers.glsl's scene_light_grid_weights) over the CPU
// arrays; returns their sum.
float weights_near(const lighting::LightGrid& grid, gpu::uvec4 cell, gpu::vec3 x, gpu::vec3 n,
                   Weights& w) {
  float total = 0.0f;
  for (std::uint32_t k = 0; k < gpu::kLightGridNeighbourCells; ++k) {
    w[k] = 0.0f;
    gpu::uvec4 neighbour;
    if (!gpu::light_grid_neighbour(grid.header(), cell, k, neighbour)) continue;
    const gpu::GpuLightGridCell c = grid.cell(gpu::light_grid_index(grid.header(), neighbour));
    if (c.count == 0) continue;
    w[k] = gpu::light_grid_weight(grid.header(), neighbour, c.power, x, n);
    total += w[k];
  }
  return total;
}

// The shaders' draw (scene_light_grid_draw): the cell whose running sum passes u_cell x total
// (its k), then a light of it by the cell's alias table.
std::uint32_t draw(const lighting::LightGrid& grid, gpu::uvec4 cell, const Weights& w, float total,
                   float u_cell, float u_light, std::uint32_t& k) {
  k = gpu::kLightGridNeighbourCells;
  if (!(total > 0.0f)) return gpu::kInvalidLight;
  const float target = u_cell * total;
  float sum = 0.0f;
  for (std::uint32_t j = 0; j < gpu::kLightGridNeighbourCells; ++j) {
    if (!(w[j] > 0.0f)) continue;
    k = j;
    sum += w[j];
    if (target < sum) break;
  }
  gpu::uvec4 neighbour;
  gpu::light_grid_neighbour(grid.header(), cell, k, neighbour);
  const gpu::GpuLightGridCell c = grid.cell(gpu::light_grid_index(grid.header(), neighbour));
  float slot_u;
  const std::uint32_t slot = gpu::light_grid_slot(c.count, u_light, slot_u);
  return gpu::light_grid_pick(grid.entry(c.first + slot), slot_u);
}

TEST(LightGrid, DrawsNearAPointFollowTheDensity) {
  const std::vector<GpuLight> lights = street_lights(2);
  const lighting::LightGrid grid(lights, powers_of(lights));
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  // Stratified, in two stages: kStrata values of u_cell give each cell's share (off its weight's
  // by at most the two strata its bounds cut); in each cell drawn, kLightStrata values of u_light
  // per light give each light's share of the cell (off by at most two strata per alias slot).
  constexpr std::uint32_t kStrata = 1u << 15;
  constexpr std::uint32_t kLightStrata = 1024;
  int points_with_lights = 0;
  for (int point = 0; point < 12; ++point) {
    // Points beside the lights (where the draws matter) and a few anywhere, facing up or down.
    gpu::vec3 x;
    if (point < 8) {
      lighting::light_grid_place(lights[(point * 83) % (lights.size() - 1)], x);
      x += gpu::vec3(0.3f * u(rng), -0.2f, 0.1f);
    } else {
      x = gpu::vec3(70.0f * u(rng) - 5.0f, 4.0f * u(rng), 25.0f * u(rng) - 2.0f);
    }
    const gpu::vec3 n(0.0f, point % 2 == 0 ? 1.0f : -1.0f, 0.0f);
    const gpu::uvec4 cell = gpu::light_grid_cell(grid.header(), x);
    Weights w;
    const float total = weights_near(grid, cell, x, n, w);
    std::array<double, gpu::kLightGridNeighbourCells> cell_share{};
    std::array<float, gpu::kLightGridNeighbourCells> first_u{};  // a u_cell that lands in cell k
    for (std::uint32_t a = 0; a < kStrata; ++a) {
      const float u_cell = (a + 0.5f) / float(kStrata);
      std::uint32_t k;
      if (draw(grid, cell, w, total, u_cell, 0.5f, k) == gpu::kInvalidLight) {
        EXPECT_EQ(total, 0.0f);
        break;
      }
      if (cell_share[k] == 0.0) first_u[k] = u_cell;
      cell_share[k] += 1.0 / kStrata;
    }
    std::map<std::uint32_t, double> frequency;
    for (std::uint32_t k = 0; k < gpu::kLightGridNeighbourCells; ++k) {
      const double share = total > 0.0f ? w[k] / total : 0.0;
      EXPECT_NEAR(cell_share[k], share, 2.0 / kStrata + 1e-6) << "point " << point << " cell " << k;
      if (cell_share[k] == 0.0) continue;
      gpu::uvec4 neighbour;
      ASSERT_TRUE(gpu::light_grid_neighbour(grid.header(), cell, k, neighbour));
      const std::uint32_t count = grid.cell(gpu::light_grid_index(grid.header(), neighbour)).count;
      ASSERT_GT(count, 0u);
      const std::uint32_t strata = count * kLightStrata;
      for (std::uint32_t b = 0; b < strata; ++b) {
        std::uint32_t kb;
        const std::uint32_t l =
            draw(grid, cell, w, total, first_u[k], (b + 0.5f) / float(strata), kb);
        ASSERT_EQ(kb, k);
        frequency[l] += share / strata;
      }
    }
    double pdf_sum = 0.0;
    for (std::uint32_t l = 0; l < lights.size(); ++l) {
      const gpu::uvec2 record = grid.light_cells()[l];
      const std::uint32_t k = gpu::light_grid_near_index(record.x, cell);
      const double pdf = k < gpu::kLightGridNeighbourCells
                             ? gpu::light_grid_pdf(w[k], total, gpu::uintBitsToFloat(record.y))
                             : 0.0;
      pdf_sum += pdf;
      const auto it = frequency.find(l);
      const double f = it == frequency.end() ? 0.0 : it->second;
      EXPECT_NEAR(f, pdf, 4.0 / kLightStrata * pdf + 1e-6) << "point " << point << " light " << l;
    }
    if (total > 0.0f) {
      EXPECT_NEAR(pdf_sum, 1.0, 1e-5) << "point " << point;  // float densities
      ++points_with_lights;
    } else {
      EXPECT_EQ(pdf_sum, 0.0) << "point " << point;
    }
    if (point < 8 && n.y > 0.0f) {
      // Lights 0.2 m above a surface facing them are reached.
      EXPECT_GT(pdf_sum, 0.0) << "a point beside a light must reach it";
    }
  }
  EXPECT_GE(points_with_lights, 4);
}

TEST(LightGrid, CellWeightsFollowPowerDistanceAndSide) {
  gpu::GpuLightGrid h{};
  h.origin_cell = gpu::vec4(0.0f, 0.0f, 0.0f, 1.0f);
  h.dims = gpu::uvec4(8u, 8u, 8u, 1u);
  const gpu::vec3 x(4.5f, 4.5f, 4.5f);  // the centre of cell (4, 4, 4)
  const gpu::vec3 up(0.0f, 1.0f, 0.0f);
  const float own = gpu::light_grid_weight(h, gpu::uvec4(4u, 4u, 4u, 0u), 2.0f, x, up);
  // x's own cell: distance floored at half an edge.
  EXPECT_FLOAT_EQ(own, 2.0f / 0.25f);
  // A cell above, one edge away: power / 1; twice the power, twice the weight.
  EXPECT_FLOAT_EQ(gpu::light_grid_weight(h, gpu::uvec4(4u, 5u, 4u, 0u), 2.0f, x, up), 2.0f);
  EXPECT_FLOAT_EQ(gpu::light_grid_weight(h, gpu::uvec4(4u, 5u, 4u, 0u), 4.0f, x, up), 4.0f);
  // A cell diagonally above: squared distance 3.
  EXPECT_FLOAT_EQ(gpu::light_grid_weight(h, gpu::uvec4(5u, 5u, 5u, 0u), 3.0f, x, up), 1.0f);
  // The cell below lies wholly behind the surface: nothing. The side cells still count.
  EXPECT_EQ(gpu::light_grid_weight(h, gpu::uvec4(4u, 3u, 4u, 0u), 2.0f, x, up), 0.0f);
  EXPECT_GT(gpu::light_grid_weight(h, gpu::uvec4(3u, 4u, 4u, 0u), 2.0f, x, up), 0.0f);
  // Facing down, the cell below counts and the one above does not.
  EXPECT_GT(gpu::light_grid_weight(h, gpu::uvec4(4u, 3u, 4u, 0u), 2.0f, x, -up), 0.0f);
  EXPECT_EQ(gpu::light_grid_weight(h, gpu::uvec4(4u, 5u, 4u, 0u), 2.0f, x, -up), 0.0f);
  // The near index inverts the neighbour offsets, and cells further away are not near.
  const gpu::uvec4 c(4u, 4u, 4u, 0u);
  for (std::uint32_t k = 0; k < gpu::kLightGridNeighbourCells; ++k) {
    gpu::uvec4 neighbour;
    ASSERT_TRUE(gpu::light_grid_neighbour(h, c, k, neighbour));
    EXPECT_EQ(gpu::light_grid_near_index(gpu::light_grid_key(neighbour), c), k);
  }
  EXPECT_EQ(gpu::light_grid_near_index(gpu::light_grid_key(gpu::uvec4(6u, 4u, 4u, 0u)), c),
            gpu::kLightGridNeighbourCells);
  EXPECT_EQ(gpu::light_grid_near_index(gpu::light_grid_key(gpu::uvec4(4u, 4u, 2u, 0u)), c),
            gpu::kLightGridNeighbourCells);
  // Absurd powers and a tiny cell: a finite weight, 27 of which still sum to a finite total.
  gpu::GpuLightGrid tiny = h;
  tiny.origin_cell.w = 1e-6f;
  const float huge = gpu::light_grid_weight(tiny, gpu::uvec4(0u), 3e38f, gpu::vec3(0.0f), up);
  EXPECT_EQ(huge, gpu::kLightGridMaxWeight);
  EXPECT_TRUE(std::isfinite(27.0f * huge));
  // At the grid's corner, neighbours outside it are refused.
  gpu::uvec4 outside;
  EXPECT_FALSE(gpu::light_grid_neighbour(h, gpu::uvec4(0u), 0u, outside));
  EXPECT_FALSE(gpu::light_grid_neighbour(h, gpu::uvec4(7u, 7u, 7u, 0u), 26u, outside));
  EXPECT_EQ(gpu::light_grid_pdf(0.0f, 1.0f, 0.25f), 0.0f);
  EXPECT_EQ(gpu::light_grid_pdf(0.5f, 2.0f, 0.0f), 0.0f);
  EXPECT_FLOAT_EQ(gpu::light_grid_pdf(0.5f, 2.0f, 0.25f), 0.0625f);
}

TEST(LightGrid, CellEdgeFollowsTheLightsDensity) {
  // 4096 points on a 16^3 lattice 1 m apart: about kTargetLightsPerCell per occupied cell.
  std::vector<GpuLight> lights;
  for (int z = 0; z < 16; ++z)
    for (int y = 0; y < 16; ++y)
      for (int x = 0; x < 16; ++x) lights.push_back(point_light(gpu::vec3(x, y, z)));
  const lighting::LightGrid grid(lights, std::vector<float>(lights.size(), 1.0f));
  const double mean = double(grid.header().dims.w) / double(grid.occupied_cells());
  EXPECT_GT(mean, lighting::LightGrid::kTargetLightsPerCell / 1.5 / 1.5 / 1.5);
  EXPECT_LT(mean, lighting::LightGrid::kTargetLightsPerCell * 1.5 * 1.5 * 1.5);
  // Two far clusters: the axes' 1024 cells bound the edge from below.
  const std::vector<GpuLight> two = {point_light(gpu::vec3(0.0f)), point_light({1e4f, 0, 0})};
  const lighting::LightGrid far(two, std::vector<float>{1.0f, 1.0f});
  EXPECT_LE(far.header().dims.x, gpu::kLightGridAxisCells);
  EXPECT_GE(far.header().origin_cell.w, 1e4f / float(gpu::kLightGridAxisCells));
  // Places too far apart for a float box (the extent overflows): no grid, rather than a guess.
  const std::vector<GpuLight> apart = {point_light({-3e38f, 0, 0}), point_light({3e38f, 0, 0})};
  const lighting::LightGrid overflow(apart, std::vector<float>{1.0f, 1.0f});
  EXPECT_EQ(overflow.header().origin_cell.w, 0.0f);
  EXPECT_EQ(overflow.light_cells()[1].x, gpu::kLightGridNoCell);
  // No placed light: no grid, nothing ever drawn.
  const std::vector<GpuLight> sun = {directional_light()};
  const lighting::LightGrid none(sun, std::vector<float>{1.0f});
  EXPECT_EQ(none.header().origin_cell.w, 0.0f);
  EXPECT_EQ(none.light_cells()[0].x, gpu::kLightGridNoCell);
}

}  // namespace
}  // namespace lantern
