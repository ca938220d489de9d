// Work counts of the project's two-level BVH traversal, per ray set (visibility_bench): nodes
// entered in the TLAS and in BLASes, instances entered (BLAS root tests that pass), triangle
// tests, and hits. A counting walk of SceneBvh's packed arrays in the order of
// shared/bvh_traverse.h (nearer child first, farther one pushed with its entry distance and
// skipped behind a closer hit, any-hit stops at the first hit); the bench checks that its hit/miss
// answers equal SceneBvh's own queries, so the counts belong to the same traversal.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <span>

#include "lighting/bvh/scene_bvh.h"
#include "shared/bvh.h"

namespace lantern::lighting::test {

struct TraversalCounts {
  std::uint64_t rays = 0;
  std::uint64_t tlas_nodes = 0;  // TLAS nodes entered
  std::uint64_t blas_nodes = 0;  // BLAS nodes entered (over all instances entered)
  std::uint64_t instances = 0;   // instances whose BLAS root box the ray reaches
  std::uint64_t triangles = 0;   // ray-triangle tests
  std::uint64_t hits = 0;        // rays that hit (mode 0) or are blocked (mode 1)
  double per_ray(std::uint64_t n) const { return rays ? static_cast<double>(n) / rays : 0.0; }
};

namespace detail {

// Ordered walk of one tree from `nodes` (its node 0 is the root); leaf(node, t_max) tests the
// leaf's primitives, may lower t_max, and returns whether it found a hit. Stops at the first hit
// when any_hit. Returns whether any leaf found a hit.
template <class Leaf>
bool counted_walk(const gpu::BvhNode* nodes, glm::vec3 origin, glm::vec3 inv_direction, float t_min,
                  float& t_max, bool any_hit, std::uint64_t& entered, Leaf&& leaf) {
  using gpu::kBvhMiss;
  const auto box = [&](const gpu::BvhNode& n) {
    return gpu::bvh_ray_box(origin, inv_direction, t_min, t_max, glm::vec3(n.bounds_min),
                            glm::vec3(n.bounds_max));
  };
  if (box(nodes[0]) == kBvhMiss) return false;
  std::uint32_t stack_node[gpu::kBvhStackSize];
  float stack_t[gpu::kBvhStackSize];
  std::uint32_t size = 0, index = 0;
  bool found = false;
  while (true) {
    const gpu::BvhNode& node = nodes[index];
    ++entered;
    bool descended = false;
    if (gpu::bvh_node_is_leaf(node)) {
      if (leaf(node, t_max)) {
        found = true;
        if (any_hit) return true;
      }
    } else {
      const std::uint32_t left = index + 1, right = gpu::bvh_node_index(node);
      const float tl = box(nodes[left]), tr = box(nodes[right]);
      const bool left_first = tl <= tr;
      const std::uint32_t near_i = left_first ? left : right, far_i = left_first ? right : left;
      const float near_t = left_first ? tl : tr, far_t = left_first ? tr : tl;
      if (near_t != kBvhMiss) {
        if (far_t != kBvhMiss) stack_node[size] = far_i, stack_t[size] = far_t, ++size;
        index = near_i;
        descended = true;
      }
    }
    if (descended) continue;
    bool popped = false;
    while (size > 0 && !popped) {
      --size;
      popped = stack_t[size] < t_max;
    }
    if (!popped) break;
    index = stack_node[size];
  }
  return found;
}

}  // namespace detail

// Adds one ray's counts (mode 0 closest hit over [tmin, tmax]; mode 1 the shadow segment
// origin -> origin + direction with the shadow epsilon, as SceneBvh::visible). Returns whether it
// hit (mode 0) or was blocked (mode 1).
inline bool count_traversal(const SceneBvh& bvh, const gpu::BvhRay& ray, std::uint32_t mode,
                            TraversalCounts& counts) {
  ++counts.rays;
  glm::vec3 origin(ray.origin), direction(ray.direction);
  float t_min = ray.origin.w, t_max = ray.direction.w;
  if (mode == 1) {
    const float t_eps = gpu::bvh_shadow_t_epsilon(origin, origin + direction);
    if (t_eps < 0.0f) return false;
    t_min = t_eps;
    t_max = 1.0f - t_eps;
  }
  const gpu::BvhSceneHeader header = bvh.header();
  if (header.tlas_node_count == 0) return false;
  const bool any_hit = mode == 1;
  const gpu::BvhNode* nodes = bvh.nodes().data();
  const bool hit = detail::counted_walk(
      nodes + header.tlas_node_offset, origin, gpu::bvh_safe_reciprocal(direction), t_min, t_max,
      any_hit, counts.tlas_nodes, [&](const gpu::BvhNode& tlas_leaf, float& t_far) {
        const gpu::BvhInstance& inst = bvh.instances()[gpu::bvh_node_index(tlas_leaf)];
        const glm::vec3 o = glm::vec3(inst.world_to_object * glm::vec4(origin, 1.0f));
        const glm::vec3 d = glm::vec3(inst.world_to_object * glm::vec4(direction, 0.0f));
        const gpu::BvhNode* blas = nodes + inst.node_offset;
        const std::uint64_t before = counts.blas_nodes;
        const bool found = detail::counted_walk(
            blas, o, gpu::bvh_safe_reciprocal(d), t_min, t_far, any_hit, counts.blas_nodes,
            [&](const gpu::BvhNode& leaf, float& t_tri) {
              bool any = false;
              const std::uint32_t first = gpu::bvh_node_index(leaf);
              for (std::uint32_t i = 0; i < gpu::bvh_node_count(leaf); ++i) {
                ++counts.triangles;
                glm::vec3 tuv;
                const gpu::BvhTriangle& tri = bvh.triangles()[inst.triangle_offset + first + i];
                if (gpu::bvh_ray_triangle(o, d, tri, t_min, t_tri, tuv)) {
                  t_tri = tuv.x;
                  any = true;
                  if (any_hit) return true;
                }
              }
              return any;
            });
        if (counts.blas_nodes != before) ++counts.instances;
        return found;
      });
  counts.hits += hit ? 1 : 0;
  return hit;
}

inline TraversalCounts count_traversal(const SceneBvh& bvh, std::span<const gpu::BvhRay> rays,
                                       std::uint32_t mode) {
  TraversalCounts counts;
  for (const gpu::BvhRay& ray : rays) (void)count_traversal(bvh, ray, mode, counts);
  return counts;
}

}  // namespace lantern::lighting::test
