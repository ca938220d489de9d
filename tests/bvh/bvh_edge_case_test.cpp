// Edge cases: empty meshes and scenes, a single triangle, axis-aligned rays with zero (and
// negative zero) direction components on box planes, non-finite rays, rays leaving a surface.
#include <gtest/gtest.h>

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <limits>

#include "tests/bvh/bvh_test_scenes.h"

namespace lantern::lighting {
namespace {

test::TestMesh quad(float y,
                    float half) {  // two triangles spanning [-half, half]^2 in xz at height y
  test::TestMesh m;
  m.positions = {{-half, y, -half}, {half, y, -half}, {half, y, half}, {-half, y, half}};
  m.indices = {0, 1, 2, 0, 2, 3};
  return m;
}

TEST(BvhEdgeCases, EmptySceneAndEmptyMeshMissEverything) {
  SceneBvh none;
  const gpu::BvhRay ray =
      gpu::bvh_make_ray(glm::vec3(0.0f), glm::vec3(0.0f, 0.0f, 1.0f), 0.0f, gpu::kBvhMiss);
  gpu::BvhHit hit;
  EXPECT_FALSE(none.trace_closest(ray, hit));
  EXPECT_FALSE(none.trace_any(ray));
  EXPECT_TRUE(none.visible(glm::vec3(0.0f), glm::vec3(1.0f)));

  const MeshBvh empty_mesh(std::vector<glm::vec3>{}, std::vector<std::uint32_t>{});
  EXPECT_TRUE(empty_mesh.empty());
  EXPECT_TRUE(empty_mesh.bounds().empty());

  SceneBvh scene;
  const std::uint32_t empty_id = scene.add_mesh(empty_mesh);
  const test::TestMesh floor = quad(0.0f, 1.0f);
  const std::uint32_t floor_id = scene.add_mesh(MeshBvh(floor.positions, floor.indices));
  const gpu::BvhRay down =
      gpu::bvh_make_ray(glm::vec3(0.1f, 1.0f, 0.2f), glm::vec3(0.0f, -1.0f, 0.0f), 0.0f, 10.0f);
  EXPECT_FALSE(scene.trace_closest(down, hit)) << "no instances placed yet";
  std::vector<BvhInstanceDesc> instances(2);
  instances[0].mesh = empty_id;
  instances[1].mesh = floor_id;
  scene.set_instances(instances);
  EXPECT_EQ(scene.header().tlas_node_count, 1u);
  ASSERT_TRUE(scene.trace_closest(down, hit));
  EXPECT_EQ(hit.instance, 1u);
  EXPECT_FLOAT_EQ(hit.t, 1.0f);
  instances.resize(1);
  scene.set_instances(instances);
  EXPECT_FALSE(scene.trace_closest(down, hit));
  EXPECT_FALSE(scene.trace_any(down));
}

TEST(BvhEdgeCases, SingleTriangleHitsBothSidesWithBarycentrics) {
  test::TestMesh tri;
  tri.positions = {{0.0f, 0.0f, 0.0f}, {1.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}};
  tri.indices = {0, 1, 2};
  const SceneBvh bvh = test::single_mesh_scene(tri);
  ASSERT_EQ(bvh.nodes().size(), 2u);  // one BLAS leaf + one TLAS leaf
  gpu::BvhHit hit;
  ASSERT_TRUE(bvh.trace_closest(
      gpu::bvh_make_ray({0.25f, 0.5f, 2.0f}, {0.0f, 0.0f, -1.0f}, 0.0f, 100.0f), hit));
  EXPECT_FLOAT_EQ(hit.t, 2.0f);
  EXPECT_FLOAT_EQ(hit.u, 0.25f);
  EXPECT_FLOAT_EQ(hit.v, 0.5f);
  EXPECT_EQ(hit.primitive, 0u);
  ASSERT_TRUE(bvh.trace_closest(
      gpu::bvh_make_ray({0.25f, 0.25f, -3.0f}, {0.0f, 0.0f, 2.0f}, 0.0f, 100.0f), hit));
  EXPECT_FLOAT_EQ(hit.t, 1.5f);
  EXPECT_FALSE(bvh.trace_closest(
      gpu::bvh_make_ray({0.6f, 0.6f, 2.0f}, {0.0f, 0.0f, -1.0f}, 0.0f, 100.0f), hit));
  EXPECT_FALSE(bvh.trace_closest(
      gpu::bvh_make_ray({0.25f, 0.5f, 2.0f}, {0.0f, 0.0f, -1.0f}, 0.0f, 1.9f), hit));
  EXPECT_FALSE(bvh.trace_closest(
      gpu::bvh_make_ray({0.25f, 0.5f, 2.0f}, {0.0f, 0.0f, 1.0f}, 0.0f, 100.0f), hit));
}

TEST(BvhEdgeCases, AxisAlignedRaysWithZeroComponentsOnBoxPlanes) {
  // Unit cubes on an integer lattice (12 triangles each): many box planes at integer coordinates.
  test::TestMesh cubes;
  for (int x = 0; x < 4; ++x)
    for (int y = 0; y < 4; ++y)
      for (int z = 0; z < 4; ++z) {
        if ((x + y + z) % 2 != 0) continue;
        const auto base = static_cast<std::uint32_t>(cubes.positions.size());
        for (int c = 0; c < 8; ++c)
          cubes.positions.emplace_back(static_cast<float>(x + (c & 1)),
                                       static_cast<float>(y + ((c >> 1) & 1)),
                                       static_cast<float>(z + ((c >> 2) & 1)));
        const std::uint32_t faces[12][3] = {{0, 1, 3}, {0, 3, 2}, {4, 6, 7}, {4, 7, 5},
                                            {0, 4, 5}, {0, 5, 1}, {2, 3, 7}, {2, 7, 6},
                                            {0, 2, 6}, {0, 6, 4}, {1, 5, 7}, {1, 7, 3}};
        for (const auto& f : faces)
          for (std::uint32_t v : f) cubes.indices.push_back(base + v);
      }
  const SceneBvh bvh = test::single_mesh_scene(cubes);
  const std::vector<test::PlacedMesh> ref = {{&cubes, glm::mat4(1.0f)}};
  const float zero = 0.0f, neg_zero = -0.0f;
  const glm::vec3 dirs[] = {{1.0f, zero, zero},  {-1.0f, neg_zero, zero}, {zero, 1.0f, neg_zero},
                            {zero, -1.0f, zero}, {neg_zero, zero, 1.0f},  {zero, zero, -1.0f}};
  int hits = 0, rays = 0;
  for (const glm::vec3& d : dirs) {
    // Origins on the lattice planes (exactly on box faces and edges) and between them.
    for (int a = 0; a <= 8; ++a)
      for (int b = 0; b <= 8; ++b) {
        const float u = 0.5f * static_cast<float>(a), v = 0.5f * static_cast<float>(b);
        glm::vec3 o = d.x != 0.0f   ? glm::vec3(d.x > 0 ? -1.0f : 5.0f, u, v)
                      : d.y != 0.0f ? glm::vec3(u, d.y > 0 ? -1.0f : 5.0f, v)
                                    : glm::vec3(u, v, d.z > 0 ? -1.0f : 5.0f);
        const gpu::BvhRay ray = gpu::bvh_make_ray(o, d, 0.0f, gpu::kBvhMiss);
        gpu::BvhHit got, want;
        const bool got_hit = bvh.trace_closest(ray, got);
        const bool want_hit = test::brute_force_closest(ref, ray, want);
        ++rays;
        ASSERT_EQ(got_hit, want_hit) << "origin " << o.x << "," << o.y << "," << o.z << " dir "
                                     << d.x << "," << d.y << "," << d.z;
        if (want_hit) {
          EXPECT_EQ(got.t, want.t);
          ++hits;
        }
        EXPECT_EQ(bvh.trace_any(ray), want_hit);
      }
  }
  EXPECT_GT(hits, rays / 4);
}

TEST(BvhEdgeCases, NonFiniteRaysMissWithoutCrashing) {
  const test::TestMesh soup = test::random_soup(200, 1.0f, 0.3f, 4);
  const SceneBvh bvh = test::single_mesh_scene(soup);
  const float nan = std::numeric_limits<float>::quiet_NaN(),
              inf = std::numeric_limits<float>::infinity();
  const gpu::BvhRay rays[] = {
      gpu::bvh_make_ray({0.0f, 0.0f, -3.0f}, {nan, 0.0f, 1.0f}, 0.0f, 100.0f),
      gpu::bvh_make_ray({nan, 0.0f, -3.0f}, {0.0f, 0.0f, 1.0f}, 0.0f, 100.0f),
      gpu::bvh_make_ray({0.0f, 0.0f, -3.0f}, {0.0f, inf, 1.0f}, 0.0f, 100.0f),
      gpu::bvh_make_ray({0.0f, 0.0f, -3.0f}, {0.0f, 0.0f, 1.0f}, nan, 100.0f),
      gpu::bvh_make_ray({0.0f, 0.0f, -3.0f}, {0.0f, 0.0f, 1.0f}, 0.0f, nan),
      gpu::bvh_make_ray({0.0f, 0.0f, -3.0f}, {0.0f, 0.0f, 0.0f}, 0.0f, 100.0f),
  };
  for (const gpu::BvhRay& ray : rays) {
    gpu::BvhHit hit;
    EXPECT_FALSE(bvh.trace_closest(ray, hit));
    EXPECT_FALSE(bvh.trace_any(ray));
  }
  // The same ray with finite values does hit (so the misses above are due to the NaNs).
  gpu::BvhHit hit;
  int finite_hits = 0;
  for (const gpu::BvhRay& ray : test::random_rays(200, 0.5f, 5))
    finite_hits += bvh.trace_closest(ray, hit) ? 1 : 0;
  EXPECT_GT(finite_hits, 0);
}

TEST(BvhEdgeCases, RaysStartingOnASurfaceDoNotHitIt) {
  // A room-like scene: floor at y=0, ceiling at y=1, a tilted far-from-origin instance as well.
  SceneBvh scene;
  const test::TestMesh floor = quad(0.0f, 1.0f), ceiling = quad(1.0f, 1.0f);
  const std::uint32_t floor_id = scene.add_mesh(MeshBvh(floor.positions, floor.indices));
  const std::uint32_t ceiling_id = scene.add_mesh(MeshBvh(ceiling.positions, ceiling.indices));
  glm::mat4 far_tilted = glm::translate(glm::mat4(1.0f), glm::vec3(1000.0f, 200.0f, -500.0f));
  far_tilted = glm::rotate(far_tilted, 0.7f, glm::normalize(glm::vec3(1.0f, 0.3f, 0.2f)));
  far_tilted = glm::scale(far_tilted, glm::vec3(50.0f));
  std::vector<BvhInstanceDesc> instances = {
      {floor_id, glm::mat4(1.0f), 0}, {ceiling_id, glm::mat4(1.0f), 1}, {floor_id, far_tilted, 2}};
  scene.set_instances(instances);

  std::mt19937 rng(3);
  std::uniform_real_distribution<float> coord(-0.95f, 0.95f), up(0.05f, 0.95f);
  for (int i = 0; i < 500; ++i) {
    const glm::vec3 on_floor(coord(rng), 0.0f, coord(rng));
    const glm::vec3 on_ceiling(coord(rng), 1.0f, coord(rng));
    const glm::vec3 inside(coord(rng), up(rng), coord(rng));
    EXPECT_TRUE(scene.visible(on_floor, on_ceiling)) << i;
    EXPECT_TRUE(scene.visible(on_floor, inside)) << i;
    EXPECT_FALSE(scene.visible(inside, on_floor - glm::vec3(0.0f, 0.5f, 0.0f)))
        << i;  // through the floor
    gpu::BvhHit hit;
    ASSERT_TRUE(scene.trace_closest(
        gpu::bvh_make_ray(on_floor, glm::vec3(0.0f, 1.0f, 0.0f), 0.0f, 10.0f), hit));
    EXPECT_EQ(hit.user_id, 1u) << "a ray leaving the floor must reach the ceiling, not the floor";

    // A point on the far tilted quad (large coordinates): leaving it along its normal is unblocked.
    const glm::vec3 local(coord(rng), 0.0f, coord(rng));
    const glm::vec3 world = glm::vec3(far_tilted * glm::vec4(local, 1.0f));
    const glm::vec3 normal = glm::normalize(
        glm::vec3(glm::transpose(glm::inverse(far_tilted)) * glm::vec4(0.0f, 1.0f, 0.0f, 0.0f)));
    EXPECT_TRUE(scene.visible(world, world + 5.0f * normal)) << i;
    EXPECT_TRUE(scene.visible(world, world - 5.0f * normal)) << i;
    EXPECT_FALSE(scene.visible(world + 5.0f * normal, world - 5.0f * normal)) << i;
  }
}

}  // namespace
}  // namespace lantern::lighting
