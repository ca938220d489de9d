// Bottom-level BVH of one triangle mesh (object space): SAH build, GPU-ready nodes and triangles
// (reordered to leaf order, shaders/shared/bvh.h), and refit for deforming meshes.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <span>
#include <vector>

#include "lighting/bvh/bvh_builder.h"
#include "shared/bvh.h"

namespace lantern::lighting {

class MeshBvh {
 public:
  MeshBvh() = default;
  // indices: three per triangle into positions. Throws lantern::InputError on an index out of
  // range, an index count not a multiple of 3, or a non-finite position.
  MeshBvh(std::span<const glm::vec3> positions, std::span<const std::uint32_t> indices,
          const BvhBuildOptions& options = {});

  // Moves the vertices (same count, same triangles) and updates triangles and node boxes bottom up
  // without changing the tree. Cheap, but the tree degrades if the mesh deforms a lot: rebuild
  // then.
  void refit(std::span<const glm::vec3> positions);

  const std::vector<gpu::BvhNode>& nodes() const { return nodes_; }
  // The vertices and triangle indices it was built (or last refit) with: for trees built from the
  // same triangles in another space (SceneBvh's merged world-space tree).
  const std::vector<glm::vec3>& positions() const { return positions_; }
  const std::vector<std::uint32_t>& indices() const { return indices_; }
  // Triangles in leaf order; BvhTriangle::v0.w holds the original triangle index.
  const std::vector<gpu::BvhTriangle>& triangles() const { return triangles_; }
  std::size_t triangle_count() const { return triangles_.size(); }
  bool empty() const { return nodes_.empty(); }
  // Object-space box of the whole mesh (empty box for an empty mesh).
  Aabb bounds() const;

 private:
  // Writes triangles_ in leaf order and, when slot_bounds is not empty, each slot's box.
  void set_triangles(std::span<const glm::vec3> positions, std::span<Aabb> slot_bounds);

  std::vector<std::uint32_t> indices_;
  std::vector<glm::vec3> positions_;
  std::vector<std::uint32_t> order_;  // leaf slot -> original triangle
  std::vector<gpu::BvhNode> nodes_;
  std::vector<gpu::BvhTriangle> triangles_;
};

}  // namespace lantern::lighting
