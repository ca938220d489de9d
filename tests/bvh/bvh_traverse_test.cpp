// Closest hit and any hit of the CPU traversal (the shared code the GPU runs) against brute force
// over every triangle, on random soups and a grid mesh.
#include <gtest/gtest.h>

#include "tests/bvh/bvh_test_scenes.h"

namespace lantern::lighting {
namespace {

// Every ray: same hit/miss and bitwise the same t as brute force; a different triangle is only
// accepted as an exact tie. Returns the number of hits (so callers can check the test saw some).
std::size_t expect_matches_brute_force(const SceneBvh& bvh,
                                       const std::vector<test::PlacedMesh>& reference,
                                       const std::vector<gpu::BvhRay>& rays) {
  std::size_t hits = 0, mismatches = 0;
  for (std::size_t i = 0; i < rays.size() && mismatches < 10; ++i) {
    gpu::BvhHit got, want;
    const bool got_hit = bvh.trace_closest(rays[i], got);
    const bool want_hit = test::brute_force_closest(reference, rays[i], want);
    bool ok = got_hit == want_hit;
    if (ok && want_hit) {
      ok = got.t == want.t;
      if (ok && (got.instance != want.instance || got.primitive != want.primitive)) {
        // Tie: the BVH's triangle must hit at the same t.
        gpu::BvhRay exact = rays[i];
        std::vector<test::PlacedMesh> just_that = {reference[got.instance]};
        gpu::BvhHit other;
        ok = test::brute_force_closest(just_that, exact, other) && other.t == want.t;
      } else if (ok) {
        ok = got.u == want.u && got.v == want.v;
      }
    }
    hits += want_hit ? 1 : 0;
    if (!ok) {
      ++mismatches;
      ADD_FAILURE() << "ray " << i << ": bvh " << got_hit << " t=" << got.t << " prim "
                    << got.primitive << " inst " << got.instance << ", brute force " << want_hit
                    << " t=" << want.t << " prim " << want.primitive << " inst " << want.instance;
    }
    // Any hit must agree with closest hit on the same segment.
    EXPECT_EQ(bvh.trace_any(rays[i]), want_hit) << "ray " << i;
  }
  return hits;
}

TEST(BvhTraverse, ClosestHitEqualsBruteForceOnRandomSoups) {
  for (std::uint32_t seed : {1u, 2u, 3u}) {
    const test::TestMesh soup = test::random_soup(1500, 4.0f, 0.6f, seed);
    const SceneBvh bvh = test::single_mesh_scene(soup);
    const std::vector<test::PlacedMesh> reference = {{&soup, glm::mat4(1.0f)}};
    const std::size_t hits =
        expect_matches_brute_force(bvh, reference, test::random_rays(3000, 5.0f, seed + 100));
    EXPECT_GT(hits, 300u) << "seed " << seed;
    EXPECT_LT(hits, 3000u) << "seed " << seed;
  }
}

TEST(BvhTraverse, ClosestHitEqualsBruteForceOnAGridMeshWithLeafSizes) {
  const test::TestMesh grid = test::grid_mesh(32, 5);
  for (std::uint32_t leaf : {1u, 4u, 8u}) {
    BvhBuildOptions options;
    options.max_leaf_size = leaf;
    const SceneBvh bvh = test::single_mesh_scene(grid, options);
    const std::vector<test::PlacedMesh> reference = {{&grid, glm::mat4(1.0f)}};
    const std::size_t hits =
        expect_matches_brute_force(bvh, reference, test::random_rays(2000, 1.5f, leaf));
    EXPECT_GT(hits, 150u);
  }
}

TEST(BvhTraverse, LongSliversWithAFarVertexAreNotCulled) {
  // Each triangle has one vertex ~1000 units away and two near the origin: the rounding of the
  // stored edges is an ulp of 1000, far more than an ulp of the near vertices' coordinates.
  std::mt19937 rng(17);
  std::uniform_real_distribution<float> near(-1.0f, 1.0f), far(-1000.0f, 1000.0f);
  test::TestMesh slivers;
  for (std::uint32_t t = 0; t < 600; ++t) {
    slivers.positions.emplace_back(far(rng), far(rng), far(rng));
    slivers.positions.emplace_back(near(rng), near(rng), near(rng));
    slivers.positions.emplace_back(near(rng), near(rng), near(rng));
    slivers.indices.insert(slivers.indices.end(),
                           {3 * t + 1, 3 * t + 2, 3 * t});  // far vertex last
  }
  const SceneBvh bvh = test::single_mesh_scene(slivers);
  const std::vector<test::PlacedMesh> reference = {{&slivers, glm::mat4(1.0f)}};
  EXPECT_GT(expect_matches_brute_force(bvh, reference, test::random_rays(2000, 1.0f, 18)), 500u);
}

TEST(BvhTraverse, BoundedSegmentsStopAtTmax) {
  const test::TestMesh soup = test::random_soup(1000, 3.0f, 0.5f, 9);
  const SceneBvh bvh = test::single_mesh_scene(soup);
  const std::vector<test::PlacedMesh> reference = {{&soup, glm::mat4(1.0f)}};
  std::vector<gpu::BvhRay> rays = test::random_rays(2000, 4.0f, 21);
  std::mt19937 rng(4);
  std::uniform_real_distribution<float> range(0.1f, 3.0f);
  for (gpu::BvhRay& ray : rays) {
    ray.origin.w = range(rng) * 0.2f;  // tmin
    ray.direction.w = range(rng);      // tmax
  }
  const std::size_t hits = expect_matches_brute_force(bvh, reference, rays);
  EXPECT_GT(hits, 100u);
}

TEST(BvhTraverse, VisibleAgreesWithClosestHitOnTheSegment) {
  const test::TestMesh soup = test::random_soup(1500, 3.0f, 0.5f, 12);
  const SceneBvh bvh = test::single_mesh_scene(soup);
  std::mt19937 rng(8);
  std::uniform_real_distribution<float> pos(-4.0f, 4.0f);
  int blocked = 0;
  const int n = 3000;
  for (int i = 0; i < n; ++i) {
    const glm::vec3 a(pos(rng), pos(rng), pos(rng)), b(pos(rng), pos(rng), pos(rng));
    gpu::BvhHit hit;
    // visible() trims less than 1e-3 of the segment at each end, so it sees every blocker this
    // does.
    const bool inner_blocked =
        bvh.trace_closest(gpu::bvh_make_ray(a, b - a, 1e-3f, 1.0f - 1e-3f), hit);
    const bool visible = bvh.visible(a, b);
    if (inner_blocked) {
      EXPECT_FALSE(visible) << "segment " << i << " blocked at t=" << hit.t;
    } else if (!visible) {
      // Then the blocker must sit within the trimmed ends.
      ASSERT_TRUE(bvh.trace_closest(gpu::bvh_make_ray(a, b - a, 0.0f, 1.0f), hit))
          << "segment " << i;
      EXPECT_TRUE(hit.t < 1e-3f || hit.t > 1.0f - 1e-3f) << "segment " << i << " t=" << hit.t;
    }
    EXPECT_EQ(bvh.trace_any(gpu::bvh_make_ray(a, b - a, 1e-3f, 1.0f - 1e-3f)), inner_blocked)
        << "segment " << i;
    blocked += visible ? 0 : 1;
  }
  EXPECT_GT(blocked, n / 10);
  EXPECT_LT(blocked, n);
}

}  // namespace
}  // namespace lantern::lighting
