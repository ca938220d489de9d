// Binned-SAH BVH builder over primitive boxes (triangles for a BLAS, instances for the TLAS).
// Multithreaded at the top of the tree; the output is bitwise identical for any thread count.
// Emits the GPU node layout of shaders/shared/bvh.h: depth first, left child next to its parent.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "engine/scene/aabb.h"
#include "shared/bvh.h"

namespace lantern::lighting {

struct BvhBuildOptions {
  // Leaves hold at most this many primitives; 4 suits triangles, 1 the TLAS (one instance a leaf).
  std::uint32_t max_leaf_size = 4;
  // SAH candidate planes per axis are bin_count - 1; more bins give slightly better trees slower.
  std::uint32_t bin_count = 16;
  // Worker threads including the caller; 0 = all hardware threads. Does not change the output.
  std::uint32_t thread_count = 0;
  // Subtrees with fewer primitives are built on the thread that reached them (task overhead).
  std::uint32_t parallel_threshold = 16384;
};

struct BvhBuildOutput {
  std::vector<gpu::BvhNode> nodes;  // empty when there are no primitives
  // Leaf slot -> input primitive index: a leaf's primitives are order[index .. index + count).
  std::vector<std::uint32_t> primitive_order;
};

// Throws lantern::InputError for bad options (max_leaf_size 0, bin_count outside [2, 32]) or
// non-finite primitive boxes.
BvhBuildOutput build_bvh(std::span<const Aabb> primitive_bounds, const BvhBuildOptions& options);

// Recomputes every node box from its leaves' primitive boxes, bottom up, keeping the topology
// (children follow their parent, so one reverse sweep visits children first).
void refit_bvh(std::span<gpu::BvhNode> nodes, std::span<const Aabb> leaf_slot_bounds);

// Box stored in a node.
Aabb node_bounds(const gpu::BvhNode& node);

}  // namespace lantern::lighting
