// SAH build: structural invariants of the emitted nodes, determinism across thread counts, refit,
// option validation, and the GPU struct sizes.
#include <gtest/gtest.h>

#include <cstddef>
#include <cstring>
#include <functional>

#include "engine/core/error.h"
#include "lighting/bvh/bvh_builder.h"
#include "tests/bvh/bvh_test_scenes.h"

namespace lantern::lighting {
namespace {

bool contains(const Aabb& outer, const Aabb& inner) {
  return glm::all(glm::lessThanEqual(outer.min, inner.min)) &&
         glm::all(glm::greaterThanEqual(outer.max, inner.max));
}

// Walks the tree checking: children inside parents, leaves within size, every slot used once.
void check_tree(const std::vector<gpu::BvhNode>& nodes, const std::vector<Aabb>& slot_bounds,
                std::uint32_t max_leaf) {
  std::vector<int> slot_uses(slot_bounds.size(), 0);
  std::uint32_t max_depth = 0;
  std::size_t visited = 0;
  std::function<void(std::uint32_t, std::uint32_t)> walk = [&](std::uint32_t n,
                                                               std::uint32_t depth) {
    ASSERT_LT(n, nodes.size());
    ++visited;
    max_depth = std::max(max_depth, depth);
    const gpu::BvhNode& node = nodes[n];
    const Aabb box = node_bounds(node);
    if (gpu::bvh_node_is_leaf(node)) {
      EXPECT_LE(gpu::bvh_node_count(node), max_leaf);
      for (std::uint32_t i = 0; i < gpu::bvh_node_count(node); ++i) {
        const std::uint32_t slot = gpu::bvh_node_index(node) + i;
        ASSERT_LT(slot, slot_bounds.size());
        ++slot_uses[slot];
        EXPECT_TRUE(contains(box, slot_bounds[slot])) << "leaf " << n << " slot " << slot;
      }
      return;
    }
    const std::uint32_t left = n + 1, right = gpu::bvh_node_index(node);
    ASSERT_GT(right, left);
    EXPECT_TRUE(contains(box, node_bounds(nodes[left])));
    EXPECT_TRUE(contains(box, node_bounds(nodes[right])));
    walk(left, depth + 1);
    walk(right, depth + 1);
  };
  walk(0, 0);
  EXPECT_EQ(visited, nodes.size()) << "unreachable nodes";
  EXPECT_LT(max_depth, gpu::kBvhStackSize);
  for (std::size_t s = 0; s < slot_uses.size(); ++s) EXPECT_EQ(slot_uses[s], 1) << "slot " << s;
}

std::vector<Aabb> soup_bounds(const test::TestMesh& mesh) {
  std::vector<Aabb> bounds(mesh.indices.size() / 3);
  for (std::size_t t = 0; t < bounds.size(); ++t)
    for (int v = 0; v < 3; ++v) bounds[t].grow(mesh.positions[mesh.indices[3 * t + v]]);
  return bounds;
}

std::vector<Aabb> slots(const std::vector<Aabb>& bounds, const std::vector<std::uint32_t>& order) {
  std::vector<Aabb> out;
  for (std::uint32_t p : order) out.push_back(bounds[p]);
  return out;
}

TEST(BvhBuild, TreeInvariantsForSeveralLeafSizesAndBinCounts) {
  const test::TestMesh soup = test::random_soup(3000, 10.0f, 0.5f, 7);
  const std::vector<Aabb> bounds = soup_bounds(soup);
  for (std::uint32_t leaf : {1u, 2u, 4u, 8u}) {
    for (std::uint32_t bins : {2u, 16u, 32u}) {
      BvhBuildOptions options;
      options.max_leaf_size = leaf;
      options.bin_count = bins;
      BvhBuildOutput out = build_bvh(bounds, options);
      SCOPED_TRACE(testing::Message() << "leaf " << leaf << " bins " << bins);
      ASSERT_FALSE(out.nodes.empty());
      EXPECT_LT(out.nodes.size(), 2 * bounds.size());
      check_tree(out.nodes, slots(bounds, out.primitive_order), leaf);
    }
  }
}

TEST(BvhBuild, IdenticalNodesForAnyThreadCount) {
  const test::TestMesh soup = test::random_soup(40000, 10.0f, 0.3f, 11);
  const std::vector<Aabb> bounds = soup_bounds(soup);
  BvhBuildOptions options;
  options.parallel_threshold = 512;  // spawn tasks deep into the tree
  options.thread_count = 1;
  const BvhBuildOutput reference = build_bvh(bounds, options);
  for (std::uint32_t threads : {2u, 3u, 8u}) {
    options.thread_count = threads;
    const BvhBuildOutput out = build_bvh(bounds, options);
    ASSERT_EQ(out.nodes.size(), reference.nodes.size()) << threads << " threads";
    EXPECT_EQ(std::memcmp(out.nodes.data(), reference.nodes.data(),
                          out.nodes.size() * sizeof(gpu::BvhNode)),
              0)
        << threads << " threads";
    EXPECT_EQ(out.primitive_order, reference.primitive_order) << threads << " threads";
  }
}

TEST(BvhBuild, IdenticalCentroidsStillSplitIntoSmallLeaves) {
  // 100 thin triangles rotated about one centre: all centroids coincide, so no SAH plane exists.
  test::TestMesh mesh;
  for (std::uint32_t i = 0; i < 100; ++i) {
    const float a = 0.0628f * static_cast<float>(i);
    const glm::vec3 d(std::cos(a), std::sin(a), 0.1f * static_cast<float>(i % 7));
    const glm::vec3 n(0.0f, 0.0f, 0.2f);
    mesh.positions.insert(mesh.positions.end(), {d, -d + n, -n});
    mesh.indices.insert(mesh.indices.end(), {3 * i, 3 * i + 1, 3 * i + 2});
  }
  const std::vector<Aabb> bounds = soup_bounds(mesh);
  const BvhBuildOutput out = build_bvh(bounds, {});
  check_tree(out.nodes, slots(bounds, out.primitive_order), 4);
}

TEST(BvhBuild, RefitMatchesFreshBoundsAndKeepsTopology) {
  test::TestMesh mesh = test::random_soup(2000, 5.0f, 0.4f, 3);
  MeshBvh bvh(mesh.positions, mesh.indices);
  const std::vector<gpu::BvhNode> before = bvh.nodes();
  for (glm::vec3& p : mesh.positions)
    p = p * 1.5f + glm::vec3(std::sin(p.y) * 2.0f, 0.0f, p.x * 0.3f);
  bvh.refit(mesh.positions);
  ASSERT_EQ(bvh.nodes().size(), before.size());
  for (std::size_t n = 0; n < before.size(); ++n) {
    EXPECT_EQ(gpu::floatBitsToUint(bvh.nodes()[n].bounds_min.w),
              gpu::floatBitsToUint(before[n].bounds_min.w));
    EXPECT_EQ(gpu::floatBitsToUint(bvh.nodes()[n].bounds_max.w),
              gpu::floatBitsToUint(before[n].bounds_max.w));
  }
  std::vector<Aabb> slot_bounds;
  for (const gpu::BvhTriangle& tri : bvh.triangles()) {
    const std::uint32_t t = gpu::floatBitsToUint(tri.v0.w);
    Aabb b;
    for (int v = 0; v < 3; ++v) b.grow(mesh.positions[mesh.indices[3 * t + v]]);
    slot_bounds.push_back(b);
  }
  check_tree(bvh.nodes(), slot_bounds, 4);
}

TEST(BvhBuild, RejectsBadOptionsAndInput) {
  const std::vector<Aabb> one(1, Aabb{glm::vec3(0.0f), glm::vec3(1.0f)});
  BvhBuildOptions options;
  options.bin_count = 1;
  EXPECT_THROW(build_bvh(one, options), InputError);
  options.bin_count = 33;
  EXPECT_THROW(build_bvh(one, options), InputError);
  options = {};
  options.max_leaf_size = 0;
  EXPECT_THROW(build_bvh(one, options), InputError);

  const std::vector<glm::vec3> positions = {glm::vec3(0.0f), glm::vec3(1.0f, 0.0f, 0.0f),
                                            glm::vec3(0.0f, 1.0f, 0.0f)};
  const std::vector<std::uint32_t> bad_index = {0, 1, 3};
  EXPECT_THROW(MeshBvh(positions, bad_index), InputError);
  const std::vector<std::uint32_t> short_indices = {0, 1};
  EXPECT_THROW(MeshBvh(positions, short_indices), InputError);
  std::vector<glm::vec3> nan_positions = positions;
  nan_positions[1].y = std::nanf("");
  const std::vector<std::uint32_t> indices = {0, 1, 2};
  EXPECT_THROW(MeshBvh(nan_positions, indices), InputError);
  MeshBvh ok(positions, indices);
  EXPECT_THROW(ok.refit(std::vector<glm::vec3>(2, glm::vec3(0.0f))), InputError);
}

TEST(BvhLayout, SharedStructSizesAndOffsets) {
  EXPECT_EQ(sizeof(gpu::BvhNode), 32u);
  EXPECT_EQ(offsetof(gpu::BvhNode, bounds_max), 16u);
  EXPECT_EQ(sizeof(gpu::BvhTriangle), 48u);
  EXPECT_EQ(offsetof(gpu::BvhTriangle, e2), 32u);
  EXPECT_EQ(sizeof(gpu::BvhInstance), 144u);
  // shaders/lib/bvh_traverse.glsl reads world_to_object as texels 4-7 and the offsets as texel 8.
  EXPECT_EQ(offsetof(gpu::BvhInstance, world_to_object), 4 * 16u);
  EXPECT_EQ(offsetof(gpu::BvhInstance, node_offset), 8 * 16u);
  EXPECT_EQ(offsetof(gpu::BvhInstance, triangle_offset), 8 * 16u + 4);
  EXPECT_EQ(offsetof(gpu::BvhInstance, user_id), 8 * 16u + 8);
  EXPECT_EQ(sizeof(gpu::BvhSceneHeader), 16u);
  EXPECT_EQ(sizeof(gpu::BvhRay), 32u);
  EXPECT_EQ(sizeof(gpu::BvhHit), 32u);
  EXPECT_EQ(offsetof(gpu::BvhHit, primitive), 16u);
}

}  // namespace
}  // namespace lantern::lighting
