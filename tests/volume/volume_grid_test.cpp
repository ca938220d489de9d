// The CPU grid (runtime/volume/volume_grid.h) read from real .vdb files: the trilinear
// convention (voxel centres at integer index coordinates, zero outside the active region), the
// brick layout, the majorant grid bounding the extinction everywhere (random probes), the
// generators (deterministic, small) and transmittance through a generated constant box.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>

#include <openvdb/tools/Interpolation.h>

#include "runtime/volume/vdb_reader.h"
#include "runtime/volume/volume_generator.h"
#include "runtime/volume/volume_set.h"
#include "shared/rng.h"
#include "tests/shared_math/statistics.h"
#include "tests/volume/vdb_fixtures.h"

namespace lantern::test {
namespace {

namespace fs = std::filesystem;

// A linear function of the index: trilinear interpolation reproduces it exactly.
float linear(glm::vec3 p) {
  return 1.0f + 0.5f * p.x + 0.25f * p.y + 2.0f * p.z + 40.0f;
}

class VolumeGridTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { setenv("LANTERN_CACHE_DIR", volume_scratch("cache").c_str(), 1); }
};

TEST_F(VolumeGridTest, TrilinearWithVoxelCentresAtIntegersAndZeroOutside) {
  // Active voxels i in [-5, -2], j in [3, 6], k in [-1, 2] (negative coordinates on purpose).
  const fs::path file = volume_scratch("linear.vdb");
  openvdb::FloatGrid::Ptr grid = openvdb::FloatGrid::create(7.0f);  // background is not density
  grid->setName("density");
  for (int k = -1; k <= 2; ++k)
    for (int j = 3; j <= 6; ++j)
      for (int i = -5; i <= -2; ++i)
        grid->tree().setValue(openvdb::Coord(i, j, k), linear(glm::vec3(i, j, k)));
  write_vdb(file, {grid});
  const runtime::VolumeGrid g = runtime::read_vdb_grid(file, "density", "test");
  EXPECT_EQ(g.active_min, glm::ivec3(-5, 3, -1));
  EXPECT_EQ(g.active_max, glm::ivec3(-2, 6, 2));
  EXPECT_EQ(g.active_voxels, 64u);
  EXPECT_EQ(g.dense_voxels(), 64u);
  // At a voxel centre: the voxel's value.
  EXPECT_FLOAT_EQ(g.sample(glm::vec3(-4, 5, 0)), linear(glm::vec3(-4, 5, 0)));
  EXPECT_FLOAT_EQ(g.voxel(glm::ivec3(-2, 6, 2)), linear(glm::vec3(-2, 6, 2)));
  // Between centres inside the active box: the linear function.
  for (glm::vec3 p : {glm::vec3(-4.5f, 3.25f, 1.75f), glm::vec3(-2.1f, 5.9f, -0.6f)})
    EXPECT_NEAR(g.sample(p), linear(p), 1e-4f) << p.x << " " << p.y << " " << p.z;
  // Outside: zero (not the file's background 7); half a voxel out: half the edge voxel.
  EXPECT_EQ(g.voxel(glm::ivec3(-6, 4, 0)), 0.0f);
  EXPECT_EQ(g.sample(glm::vec3(-6.0f, 4.0f, 0.0f)), 0.0f);
  EXPECT_EQ(g.sample(glm::vec3(-1.0f, 4.0f, 0.0f)), 0.0f);
  EXPECT_EQ(g.sample(glm::vec3(-3.0f, 4.0f, 30.0f)), 0.0f);
  EXPECT_NEAR(g.sample(glm::vec3(-5.5f, 4.0f, 0.0f)), 0.5f * linear(glm::vec3(-5, 4, 0)), 1e-4f);
  EXPECT_NEAR(g.sample(glm::vec3(-3.0f, 6.75f, 0.0f)), 0.25f * linear(glm::vec3(-3, 6, 0)), 1e-4f);
  // The whole support is covered by cells aligned to multiples of 8.
  EXPECT_EQ(g.cell_origin.x % 8, 0);
  EXPECT_LE(g.cell_origin.x, -6);
  EXPECT_GE(g.cell_origin.x + 8 * int(g.cell_counts.x), 0);
}

TEST_F(VolumeGridTest, InactiveVoxelsReadZeroAndEmptyBricksAreNotStored) {
  const fs::path file = volume_scratch("two_voxels.vdb");
  openvdb::FloatGrid::Ptr grid = openvdb::FloatGrid::create(0.0f);
  grid->setName("density");
  grid->tree().setValue(openvdb::Coord(1, 1, 1), 2.0f);
  grid->tree().setValue(openvdb::Coord(60, 1, 1), 3.0f);
  grid->tree().setValueOff(openvdb::Coord(30, 1, 1), 9.0f);  // an inactive value is not density
  write_vdb(file, {grid});
  const runtime::VolumeGrid g = runtime::read_vdb_grid(file, "density", "test");
  EXPECT_EQ(g.brick_count(), 2u);
  EXPECT_EQ(g.voxel(glm::ivec3(30, 1, 1)), 0.0f);
  EXPECT_EQ(g.voxel(glm::ivec3(60, 1, 1)), 3.0f);
  EXPECT_EQ(g.bytes(), g.cells.size() * 16 + 2 * gpu::kVolumeBrickVoxels * 4);
}

// Random values over a box that crosses cell faces on every axis (negative coordinates too):
// the bricks' trilinear lookup (each cell's apron holding its +x/+y/+z neighbours' first layer)
// agrees with OpenVDB's own BoxSampler at random points, near faces, edges and corners included.
TEST_F(VolumeGridTest, TrilinearAcrossCellFacesMatchesOpenVdbsBoxSampler) {
  const fs::path file = volume_scratch("random_box.vdb");
  openvdb::FloatGrid::Ptr grid = openvdb::FloatGrid::create(0.0f);
  grid->setName("density");
  gpu::uint rng = gpu::rng_init(glm::uvec2(5u), 0u, 77u, 0u);
  for (int k = -9; k <= 10; ++k)
    for (int j = -3; j <= 17; ++j)
      for (int i = -17; i <= 1; ++i)
        grid->tree().setValue(openvdb::Coord(i, j, k), 0.1f + gpu::rng_next_float(rng));
  write_vdb(file, {grid});
  const runtime::VolumeGrid g = runtime::read_vdb_grid(file, "density", "test");
  const openvdb::FloatGrid::ConstAccessor acc = grid->getConstAccessor();
  const glm::vec3 lo(-19.0f, -5.0f, -11.0f), hi(3.0f, 19.0f, 12.0f);
  for (int n = 0; n < 20000; ++n) {
    glm::vec3 p = lo + (hi - lo) * glm::vec3(gpu::rng_next_float(rng), gpu::rng_next_float(rng),
                                             gpu::rng_next_float(rng));
    if (n % 4 == 0) p.x = 8.0f * std::floor(p.x / 8.0f) - 0.5f;  // between two cells in x
    const float expected =
        openvdb::tools::BoxSampler::sample(acc, openvdb::Vec3R(p.x, p.y, p.z));
    ASSERT_NEAR(g.sample(p), expected, 1e-5f * (1.0f + expected))
        << n << ": " << p.x << " " << p.y << " " << p.z;
  }
}

TEST_F(VolumeGridTest, ActiveTilesAreExpanded) {
  const fs::path file = volume_scratch("tile.vdb");
  openvdb::FloatGrid::Ptr grid = openvdb::FloatGrid::create(0.0f);
  grid->setName("density");
  grid->fill(openvdb::CoordBBox(openvdb::Coord(0), openvdb::Coord(15)), 0.75f, true);
  grid->pruneGrid();
  ASSERT_GT(grid->tree().activeTileCount(), 0u);
  write_vdb(file, {grid});
  const runtime::VolumeGrid g = runtime::read_vdb_grid(file, "density", "test");
  EXPECT_EQ(g.active_voxels, 16u * 16u * 16u);
  EXPECT_EQ(g.voxel(glm::ivec3(9, 3, 15)), 0.75f);
  // The 2^3 cells the tile covers, and the cells on their -x, -y, -z sides whose apron holds
  // the tile's first layer: 3^3 bricks.
  EXPECT_EQ(g.brick_count(), 27u);
  EXPECT_EQ(g.sample(glm::vec3(-0.5f, 3.0f, 3.0f)), 0.375f);
}

// Every channel of sigma_t at random points is <= the majorant of the cell holding the point,
// and >= the cell's control (min density) extinction.
TEST_F(VolumeGridTest, MajorantBoundsTheExtinctionEverywhere) {
  for (VolumeGeneratorType type :
       {VolumeGeneratorType::SmokePlume, VolumeGeneratorType::GroundFog}) {
    Volume v;
    v.generator = VolumeGenerator{type, 3, glm::vec3(3.0f, 3.0f, 3.0f), 0.1f};
    v.scattering = glm::vec3(0.8f, 1.0f, 1.3f);
    v.absorption = glm::vec3(0.2f, 0.1f, 0.0f);
    v.density_scale = 2.0f;
    v.where = "test";
    const runtime::VolumeGrid g = runtime::load_volume_grid(v);
    ASSERT_GT(g.brick_count(), 0u);
    const gpu::GpuVolume record = runtime::volume_record(v, g, glm::mat4(1.0f), 0u);
    const gpu::VolumeGridView view = g.view();
    gpu::uint rng = gpu::rng_init(glm::uvec2(21u), 0u, 201u, 0u);
    const glm::vec3 lo = glm::vec3(record.support_min), hi = glm::vec3(record.support_max);
    int checked = 0;
    for (int i = 0; i < 200000; ++i) {
      const glm::vec3 u(gpu::rng_next_float(rng), gpu::rng_next_float(rng),
                        gpu::rng_next_float(rng));
      const glm::vec3 p = lo + u * (hi - lo);
      const float density = gpu::volume_density_index(view, record, p);
      const glm::vec3 sigma_t = gpu::volume_extinction(record, density);
      const float majorant = gpu::volume_majorant_index(view, record, p);
      const gpu::GpuVolumeCell cell =
          g.cells[gpu::volume_cell_index(record, gpu::volume_cell_of(record, p))];
      for (int c = 0; c < 3; ++c) ASSERT_LE(sigma_t[c], majorant * (1.0f + 1e-6f)) << i;
      ASSERT_GE(density, cell.min_density * (1.0f - 1e-6f)) << i;
      checked += density > 0.0f;
    }
    EXPECT_GT(checked, 1000) << "probes mostly missed the medium";
  }
}

TEST_F(VolumeGridTest, GeneratorsAreDeterministicAndSmall) {
  for (VolumeGeneratorType type : {VolumeGeneratorType::Constant, VolumeGeneratorType::SmokePlume,
                                   VolumeGeneratorType::GroundFog}) {
    const VolumeGenerator gen{type, 7, glm::vec3(4.0f, 2.0f, 4.0f), 0.1f};
    const fs::path a = volume_scratch("gen_a.vdb"), b = volume_scratch("gen_b.vdb");
    runtime::write_generated_volume(gen, a);
    runtime::write_generated_volume(gen, b);
    const runtime::VolumeGrid ga = runtime::read_vdb_grid(a, "density", "a");
    const runtime::VolumeGrid gb = runtime::read_vdb_grid(b, "density", "b");
    SCOPED_TRACE(volume_generator_name(type));
    EXPECT_EQ(ga.values, gb.values);
    EXPECT_EQ(ga.active_voxels, gb.active_voxels);
    EXPECT_GT(ga.active_voxels, 1000u);
    EXPECT_LE(ga.active_voxels, 40u * 20u * 40u);
    EXPECT_LE(ga.max_value, 1.0f);
    // Another seed, another grid (the constant box has no randomness).
    if (type != VolumeGeneratorType::Constant) {
      VolumeGenerator other = gen;
      other.seed = 8;
      runtime::write_generated_volume(other, b);
      EXPECT_NE(runtime::read_vdb_grid(b, "density", "b").values, ga.values);
    }
  }
  const VolumeGenerator box{VolumeGeneratorType::Constant, 1, glm::vec3(1.0f, 0.5f, 2.0f), 0.25f};
  const fs::path cached = runtime::generated_volume_file(box);
  EXPECT_EQ(cached, runtime::generated_volume_file(box));
  EXPECT_EQ(cached.parent_path(), volume_scratch("cache") / "volumes");
  const runtime::VolumeGrid g = runtime::read_vdb_grid(cached, "density", "box");
  EXPECT_EQ(g.active_voxels, 4u * 2u * 8u);
  // Voxel (0,0,0)'s centre is half a voxel inside the box's corner (-0.5, 0, -1).
  const glm::vec3 centre = glm::vec3(g.index_to_world * glm::vec4(0, 0, 0, 1));
  EXPECT_NEAR(centre.x, -0.5f + 0.125f, 1e-6f);
  EXPECT_NEAR(centre.y, 0.125f, 1e-6f);
  EXPECT_NEAR(centre.z, -1.0f + 0.125f, 1e-6f);
}

// The constant box's trilinear ramp at its faces integrates like a sharp face, so the optical
// depth straight through it is sigma_t * size: ratio tracking through the real grid (shared
// lookups, one majorant for the whole ray) converges to exp(-sigma_t * size).

TEST_F(VolumeGridTest, RatioTrackingThroughAGeneratedConstantBox) {
  Volume v;
  v.generator =
      VolumeGenerator{VolumeGeneratorType::Constant, 1, glm::vec3(2.0f, 1.0f, 1.0f), 0.125f};
  v.scattering = glm::vec3(0.5f, 0.3f, 0.1f);
  v.absorption = glm::vec3(0.1f);
  v.where = "test";
  const runtime::VolumeGrid g = runtime::load_volume_grid(v);
  const gpu::VolumeMedium m{g.view(), runtime::volume_record(v, g, glm::mat4(1.0f), 0u)};
  // A world ray along +x through the middle, carried into index space (t stays in metres).
  const glm::vec3 o = glm::vec3(m.volume.world_to_index * glm::vec4(-3.0f, 0.5f, 0.0f, 1.0f));
  const glm::vec3 d = glm::vec3(m.volume.world_to_index * glm::vec4(1.0f, 0.0f, 0.0f, 0.0f));
  const float majorant = g.max_value * m.volume.absorption.w;
  gpu::uint rng = gpu::rng_init(glm::uvec2(23u), 0u, 202u, 0u);
  double sum[3] = {0, 0, 0}, sum_cells[3] = {0, 0, 0};
  const int n = 100000;
  for (int i = 0; i < n; ++i) {
    const glm::vec3 t = gpu::ratio_tracking(m, 0u, o, d, 0.0f, 6.0f, majorant, 0.0f, rng);
    const glm::vec3 cells =
        gpu::volume_transmittance_residual(m.grid, 0u, m.volume, o, d, 0.0f, 6.0f, 0.0f, rng);
    for (int c = 0; c < 3; ++c) {
      sum[c] += t[c];
      sum_cells[c] += cells[c];
    }
  }
  for (int c = 0; c < 3; ++c) {
    const double expected = std::exp(-2.0 * double(v.scattering[c] + v.absorption[c]));
    // Per-sample values lie in [0, 1]: the standard error is at most 0.5 / sqrt(n).
    EXPECT_NEAR(sum[c] / n, expected, 4.0 * 0.5 / std::sqrt(double(n))) << c;
    EXPECT_NEAR(sum_cells[c] / n, expected, 4.0 * 0.5 / std::sqrt(double(n))) << c;
  }
}

}  // namespace
}  // namespace lantern::test

namespace lantern::test {
namespace {

// exp(-optical depth) by fine quadrature (midpoint rule) of the shared trilinear lookup.
glm::dvec3 quadrature_transmittance(const gpu::VolumeMedium& m, glm::vec3 o, glm::vec3 d, float t0,
                                    float t1) {
  const int steps = 20000;
  glm::dvec3 tau(0.0);
  const double dt = double(t1 - t0) / steps;
  for (int i = 0; i < steps; ++i)
    tau += glm::dvec3(gpu::medium_extinction(m, 0u, o + (t0 + float((i + 0.5) * dt)) * d)) * dt;
  return glm::exp(-tau);
}

// The majorant DDA and both grid estimators against quadrature, on a plume seen along
// oblique rays (cells crossed in every direction, segments of every length).
TEST_F(VolumeGridTest, GridTransmittanceOverTheMajorantCellsMatchesQuadrature) {
  Volume v;
  v.generator =
      VolumeGenerator{VolumeGeneratorType::SmokePlume, 4, glm::vec3(2.0f, 3.0f, 2.0f), 0.05f};
  v.scattering = glm::vec3(2.0f, 1.5f, 1.0f);
  v.absorption = glm::vec3(0.5f);
  v.where = "test";
  const runtime::VolumeGrid g = runtime::load_volume_grid(v);
  const gpu::VolumeMedium m{g.view(), runtime::volume_record(v, g, glm::mat4(1.0f), 0u)};
  struct Ray {
    glm::vec3 from, to;
  };
  const Ray rays[] = {{{-2.0f, 0.5f, -0.3f}, {2.0f, 1.2f, 0.4f}},
                      {{0.1f, 4.0f, 0.05f}, {-0.05f, -0.5f, 0.0f}},
                      {{1.5f, 0.2f, 1.5f}, {-1.5f, 2.5f, -1.2f}}};
  // 5 standard errors: 18 correlated checks (3 rays x 3 channels x 2 estimators), one seed per ray.
  gpu::uint seed = 203u;
  for (const Ray& r : rays) {
    gpu::uint rng = gpu::rng_init(glm::uvec2(25u), 0u, seed++, 0u);
    const glm::vec3 dw = glm::normalize(r.to - r.from);
    const float length = glm::length(r.to - r.from);
    const glm::vec3 o = glm::vec3(m.volume.world_to_index * glm::vec4(r.from, 1.0f));
    const glm::vec3 d = glm::vec3(m.volume.world_to_index * glm::vec4(dw, 0.0f));
    const glm::dvec3 expected = quadrature_transmittance(m, o, d, 0.0f, length);
    test::RunningStats ratio[3], residual[3];
    for (int i = 0; i < 40000; ++i) {
      const glm::vec3 a =
          gpu::volume_transmittance_ratio(m.grid, 0u, m.volume, o, d, 0.0f, length, 0.0f, rng);
      const glm::vec3 b =
          gpu::volume_transmittance_residual(m.grid, 0u, m.volume, o, d, 0.0f, length, 0.0f, rng);
      for (int c = 0; c < 3; ++c) {
        ratio[c].add(a[c]);
        residual[c].add(b[c]);
      }
    }
    for (int c = 0; c < 3; ++c) {
      std::printf(
          "grid transmittance ch%d: quadrature %.5f, ratio %.5f +- %.5f, residual %.5f "
          "+- %.5f\n",
          c, expected[c], ratio[c].mean(), ratio[c].standard_error(), residual[c].mean(),
          residual[c].standard_error());
      EXPECT_NEAR(ratio[c].mean(), expected[c], 5.0 * ratio[c].standard_error() + 1e-4);
      EXPECT_NEAR(residual[c].mean(), expected[c], 5.0 * residual[c].standard_error() + 1e-4);
    }
    EXPECT_LT(expected.x, 0.98) << "the ray should cross some smoke";
  }
}

}  // namespace
}  // namespace lantern::test

namespace lantern::test {
namespace {

// Two grids packed into shared cell and value arrays (what the GPU uploads) sample exactly as
// each grid alone, through their records' first cells and the rebased bricks.
TEST_F(VolumeGridTest, PackedGridsSampleLikeTheirOwn) {
  Volume fog, plume;
  fog.generator = VolumeGenerator{VolumeGeneratorType::GroundFog, 2, glm::vec3(2.0f), 0.1f};
  plume.generator =
      VolumeGenerator{VolumeGeneratorType::SmokePlume, 3, glm::vec3(1.0f, 2.0f, 1.0f), 0.05f};
  fog.where = plume.where = "test";
  const runtime::VolumeGrid a = runtime::load_volume_grid(fog);
  const runtime::VolumeGrid b = runtime::load_volume_grid(plume);
  std::vector<gpu::GpuVolumeCell> cells;
  std::vector<float> values;
  const std::uint32_t first_a = runtime::pack_volume_grid(a, cells, values);
  const std::uint32_t first_b = runtime::pack_volume_grid(b, cells, values);
  EXPECT_EQ(first_a, 0u);
  EXPECT_EQ(first_b, a.cells.size());
  EXPECT_EQ(values.size(), a.values.size() + b.values.size());
  const gpu::VolumeGridView packed{cells.data(), values.data()};
  const gpu::GpuVolume ra = runtime::volume_record(fog, a, glm::mat4(1.0f), first_a);
  const gpu::GpuVolume rb = runtime::volume_record(plume, b, glm::mat4(1.0f), first_b);
  gpu::uint rng = gpu::rng_init(glm::uvec2(27u), 0u, 204u, 0u);
  for (int i = 0; i < 20000; ++i) {
    const glm::vec3 u(gpu::rng_next_float(rng), gpu::rng_next_float(rng), gpu::rng_next_float(rng));
    const glm::vec3 pa = glm::vec3(ra.support_min) + u * glm::vec3(ra.support_max - ra.support_min);
    const glm::vec3 pb = glm::vec3(rb.support_min) + u * glm::vec3(rb.support_max - rb.support_min);
    ASSERT_EQ(gpu::volume_density_index(packed, ra, pa), a.sample(pa));
    ASSERT_EQ(gpu::volume_density_index(packed, rb, pb), b.sample(pb));
  }
}

}  // namespace
}  // namespace lantern::test
