// Two-level BVH: instances with rotation, non-uniform scale and translation; TLAS rebuilds per
// frame; BLAS refit of a deforming mesh — each checked against brute force over all triangles.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "engine/core/error.h"
#include "tests/bvh/bvh_test_scenes.h"

namespace lantern::lighting {
namespace {

glm::mat4 random_transform(std::mt19937& rng) {
  std::uniform_real_distribution<float> pos(-8.0f, 8.0f), scale(0.3f, 2.0f),
      angle(0.0f, 6.2831853f);
  glm::mat4 m = glm::translate(glm::mat4(1.0f), glm::vec3(pos(rng), pos(rng), pos(rng)));
  m = glm::rotate(m, angle(rng), test::random_direction(rng));
  return glm::scale(m, glm::vec3(scale(rng), scale(rng), scale(rng)));
}

class BvhTwoLevel : public testing::Test {
 protected:
  void SetUp() override {
    meshes_ = {test::random_soup(400, 1.0f, 0.3f, 1), test::grid_mesh(12, 2),
               test::random_soup(200, 0.5f, 0.2f, 3)};
    reset();
  }

  // A fresh scene BVH over the meshes (instance identities, and which fixed ones moved, start
  // over).
  void reset() {
    bvh_ = SceneBvh();
    for (const test::TestMesh& m : meshes_) bvh_.add_mesh(MeshBvh(m.positions, m.indices));
  }

  // Places `count` instances; every `fixed_every`-th one (0: none) is declared fixed.
  void place(std::uint32_t seed, std::size_t count, std::size_t fixed_every = 0) {
    std::mt19937 rng(seed);
    descs_.clear();
    for (std::size_t i = 0; i < count; ++i) {
      BvhInstanceDesc d;
      d.mesh = static_cast<std::uint32_t>(i % meshes_.size());
      d.object_to_world = random_transform(rng);
      d.user_id = 1000 + static_cast<std::uint32_t>(i);
      d.fixed = fixed_every != 0 && i % fixed_every == 0;
      descs_.push_back(d);
    }
    bvh_.set_instances(descs_);
  }

  // Against the triangles moved into world space (merged triangles are tested in world space, so
  // t agrees within rounding): the same hit/miss on >= 99.9% of rays and, on agreeing hits, the
  // same instance, primitive and user id. Returns the number of hits.
  std::size_t check_world_space(std::uint32_t seed) const {
    std::vector<test::TestMesh> world(descs_.size());
    std::vector<test::PlacedMesh> ref;
    for (std::size_t i = 0; i < descs_.size(); ++i) {
      world[i] = meshes_[descs_[i].mesh];
      for (glm::vec3& p : world[i].positions)
        p = glm::vec3(descs_[i].object_to_world * glm::vec4(p, 1.0f));
      ref.push_back({&world[i], glm::mat4(1.0f)});
    }
    std::size_t agree = 0, hits = 0, same_triangle = 0;
    const std::vector<gpu::BvhRay> rays = test::random_rays(2000, 10.0f, seed);
    for (const gpu::BvhRay& ray : rays) {
      gpu::BvhHit got, want;
      const bool got_hit = bvh_.trace_closest(ray, got);
      const bool want_hit = test::brute_force_closest(ref, ray, want);
      if (got_hit != want_hit || bvh_.trace_any(ray) != want_hit) continue;
      ++agree;
      if (!want_hit) continue;
      ++hits;
      EXPECT_NEAR(got.t, want.t, 1e-3f * want.t + 1e-4f);
      if (got.instance == want.instance && got.primitive == want.primitive) {
        ++same_triangle;
        EXPECT_EQ(got.user_id, descs_[want.instance].user_id);
      }
    }
    EXPECT_GE(agree, rays.size() * 999 / 1000);
    EXPECT_GE(same_triangle, hits * 99 / 100);
    return hits;
  }

  std::vector<test::PlacedMesh> reference() const {
    std::vector<test::PlacedMesh> out;
    for (std::size_t i = 0; i < descs_.size(); ++i)
      out.push_back({&meshes_[descs_[i].mesh], bvh_.instances()[i].world_to_object});
    return out;
  }

  // Exact agreement with the object-space brute force; returns the number of hits.
  std::size_t check_exact(std::uint32_t seed) const {
    const std::vector<test::PlacedMesh> ref = reference();
    std::size_t hits = 0;
    int failures = 0;
    for (const gpu::BvhRay& ray : test::random_rays(2000, 10.0f, seed)) {
      gpu::BvhHit got, want;
      const bool got_hit = bvh_.trace_closest(ray, got);
      const bool want_hit = test::brute_force_closest(ref, ray, want);
      EXPECT_EQ(bvh_.trace_any(ray), want_hit);
      if (got_hit != want_hit || (want_hit && got.t != want.t)) {
        if (++failures < 10)
          ADD_FAILURE() << "bvh " << got_hit << " t=" << got.t << " inst " << got.instance
                        << ", brute force " << want_hit << " t=" << want.t << " inst "
                        << want.instance;
        continue;
      }
      if (want_hit) {
        ++hits;
        if (got.instance == want.instance && got.primitive == want.primitive) {
          EXPECT_EQ(got.u, want.u);
          EXPECT_EQ(got.v, want.v);
        }
        EXPECT_EQ(got.user_id, descs_[got.instance].user_id);
      }
    }
    return hits;
  }

  std::vector<test::TestMesh> meshes_;
  std::vector<BvhInstanceDesc> descs_;
  SceneBvh bvh_;
};

TEST_F(BvhTwoLevel, ClosestHitEqualsBruteForceOverRotatedScaledInstances) {
  place(5, 30);
  EXPECT_EQ(bvh_.header().instance_count, 30u);
  EXPECT_EQ(bvh_.header().tlas_node_count, 2u * 30u - 1u);
  EXPECT_GT(check_exact(40), 200u);
}

TEST_F(BvhTwoLevel, AgreesWithWorldSpaceTrianglesWithinRounding) {
  place(6, 20);
  // Independent reference: the triangles moved into world space, tested with untransformed rays.
  std::vector<test::TestMesh> world(descs_.size());
  std::vector<test::PlacedMesh> ref;
  for (std::size_t i = 0; i < descs_.size(); ++i) {
    world[i] = meshes_[descs_[i].mesh];
    for (glm::vec3& p : world[i].positions)
      p = glm::vec3(descs_[i].object_to_world * glm::vec4(p, 1.0f));
    ref.push_back({&world[i], glm::mat4(1.0f)});
  }
  int agree = 0, hits = 0;
  const std::vector<gpu::BvhRay> rays = test::random_rays(2000, 10.0f, 41);
  for (const gpu::BvhRay& ray : rays) {
    gpu::BvhHit got, want;
    const bool got_hit = bvh_.trace_closest(ray, got);
    const bool want_hit = test::brute_force_closest(ref, ray, want);
    if (got_hit != want_hit) continue;
    ++agree;
    if (!want_hit) continue;
    ++hits;
    EXPECT_NEAR(got.t, want.t, 1e-3f * want.t + 1e-4f);
  }
  EXPECT_GE(agree, static_cast<int>(rays.size()) * 999 / 1000);
  EXPECT_GT(hits, 100);
}

TEST_F(BvhTwoLevel, TlasRebuiltEachFrameFollowsMovingInstances) {
  for (std::uint32_t frame = 0; frame < 4; ++frame) {
    place(100 + frame, 12 + 5 * frame);
    EXPECT_GT(check_exact(200 + frame), 50u) << "frame " << frame;
  }
}

TEST_F(BvhTwoLevel, RefitDeformingMeshStillEqualsBruteForce) {
  place(7, 24);
  for (int step = 1; step <= 3; ++step) {
    for (glm::vec3& p : meshes_[0].positions)
      p +=
          0.3f * glm::vec3(std::sin(3.0f * p.y + step), std::cos(2.0f * p.z), std::sin(p.x * step));
    bvh_.refit_mesh(0, meshes_[0].positions);
    bvh_.set_instances(descs_);
    EXPECT_GT(check_exact(300 + step), 100u) << "step " << step;
  }
}

TEST_F(BvhTwoLevel, FixedInstancesMergeIntoOneWorldSpaceTree) {
  place(8, 24, 1);  // all fixed
  EXPECT_EQ(bvh_.merged_instance_count(), 24u);
  EXPECT_EQ(bvh_.instance_count(), 24u);
  EXPECT_EQ(bvh_.instances().size(), 25u);     // + the merged tree's record
  EXPECT_EQ(bvh_.header().tlas_node_count, 1u);  // one leaf: the merged tree
  EXPECT_GT(check_world_space(50), 100u);
  reset();
  place(9, 24, 3);  // a third fixed: merged and instanced under one TLAS
  EXPECT_EQ(bvh_.merged_instance_count(), 8u);
  EXPECT_EQ(bvh_.header().tlas_node_count, 2u * (16u + 1u) - 1u);
  EXPECT_GT(check_world_space(51), 100u);
}

TEST_F(BvhTwoLevel, FixedInstanceThatMovesLeavesTheMergedTree) {
  place(10, 18, 1);
  const std::uint64_t generation = bvh_.blas_generation();
  bvh_.set_instances(descs_);  // nothing moved: the merged tree stays
  EXPECT_EQ(bvh_.blas_generation(), generation);
  descs_[4].object_to_world = glm::translate(descs_[4].object_to_world, glm::vec3(0.5f, 0, 0));
  bvh_.set_instances(descs_);
  EXPECT_EQ(bvh_.merged_instance_count(), 17u);
  EXPECT_NE(bvh_.blas_generation(), generation);
  EXPECT_GT(check_world_space(52), 80u);
  // It stays out when it moves again, and the others stay merged (no rebuild).
  const std::uint64_t after = bvh_.blas_generation();
  descs_[4].object_to_world = glm::translate(descs_[4].object_to_world, glm::vec3(0, 0.5f, 0));
  bvh_.set_instances(descs_);
  EXPECT_EQ(bvh_.merged_instance_count(), 17u);
  EXPECT_EQ(bvh_.blas_generation(), after);
  EXPECT_GT(check_world_space(53), 80u);
}

TEST_F(BvhTwoLevel, RefitMeshTakesItsFixedInstancesOutOfTheMergedTree) {
  place(11, 12, 1);
  for (glm::vec3& p : meshes_[1].positions) p.y += 0.2f * std::sin(3.0f * p.x);
  bvh_.refit_mesh(1, meshes_[1].positions);
  bvh_.set_instances(descs_);
  EXPECT_EQ(bvh_.merged_instance_count(), 8u);  // mesh 1's four instances are instanced now
  EXPECT_GT(check_world_space(54), 100u);
}

TEST_F(BvhTwoLevel, RejectsUnknownMeshAndSingularTransform) {
  BvhInstanceDesc d;
  d.mesh = 99;
  EXPECT_THROW(bvh_.set_instances({&d, 1}), InputError);
  d.mesh = 0;
  d.object_to_world = glm::scale(glm::mat4(1.0f), glm::vec3(1.0f, 0.0f, 1.0f));
  EXPECT_THROW(bvh_.set_instances({&d, 1}), InputError);
  EXPECT_THROW(bvh_.refit_mesh(7, meshes_[0].positions), InputError);
}

}  // namespace
}  // namespace lantern::lighting
