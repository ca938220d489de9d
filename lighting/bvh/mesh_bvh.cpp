// Bottom-level BVH of one mesh: validates the mesh, builds over triangle boxes, stores triangles
// as (v0, e1, e2) in leaf order, and refits after vertices move.
#include "lighting/bvh/mesh_bvh.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "engine/core/error.h"

namespace lantern::lighting {
namespace {

void check_positions(std::span<const glm::vec3> positions, const char* what) {
  for (std::size_t i = 0; i < positions.size(); ++i) {
    const glm::vec3& p = positions[i];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      throw InputError(
          fmt::format("{}: vertex {} is not finite ({}, {}, {})", what, i, p.x, p.y, p.z));
  }
}

// Box of a triangle, widened by a few ulps of its largest coordinate: the traversal tests the
// stored (v0, v1 - v0, v2 - v0), whose rounding can move the edges of a triangle with a far-off
// vertex by an ulp of that vertex, beyond a box taken from the exact vertices.
Aabb triangle_bounds(std::span<const glm::vec3> positions, const std::uint32_t* tri) {
  Aabb box;
  box.grow(positions[tri[0]]);
  box.grow(positions[tri[1]]);
  box.grow(positions[tri[2]]);
  const glm::vec3 magnitude = glm::max(glm::abs(box.min), glm::abs(box.max));
  const float pad = std::max(magnitude.x, std::max(magnitude.y, magnitude.z)) * (1.0f / (1 << 21));
  box.min -= pad;
  box.max += pad;
  return box;
}

}  // namespace

MeshBvh::MeshBvh(std::span<const glm::vec3> positions, std::span<const std::uint32_t> indices,
                 const BvhBuildOptions& options)
    : indices_(indices.begin(), indices.end()), positions_(positions.begin(), positions.end()) {
  if (indices.size() % 3 != 0)
    throw InputError(fmt::format("mesh BVH: {} indices is not a multiple of 3", indices.size()));
  for (std::size_t i = 0; i < indices.size(); ++i) {
    if (indices[i] >= positions.size())
      throw InputError(fmt::format("mesh BVH: index {} (at {}) is out of range for {} vertices",
                                   indices[i], i, positions.size()));
  }
  check_positions(positions, "mesh BVH");
  const std::size_t triangle_count = indices.size() / 3;
  std::vector<Aabb> bounds(triangle_count);
  for (std::size_t t = 0; t < triangle_count; ++t)
    bounds[t] = triangle_bounds(positions, &indices_[3 * t]);
  BvhBuildOutput built = build_bvh(bounds, options);
  nodes_ = std::move(built.nodes);
  order_ = std::move(built.primitive_order);
  set_triangles(positions, {});
}

void MeshBvh::set_triangles(std::span<const glm::vec3> positions, std::span<Aabb> slot_bounds) {
  triangles_.resize(order_.size());
  for (std::size_t slot = 0; slot < order_.size(); ++slot) {
    const std::uint32_t t = order_[slot];
    if (!slot_bounds.empty()) slot_bounds[slot] = triangle_bounds(positions, &indices_[3 * t]);
    const glm::vec3 v0 = positions[indices_[3 * t]];
    const glm::vec3 v1 = positions[indices_[3 * t + 1]];
    const glm::vec3 v2 = positions[indices_[3 * t + 2]];
    gpu::BvhTriangle& tri = triangles_[slot];
    tri.v0 = glm::vec4(v0, glm::uintBitsToFloat(t));
    tri.e1 = glm::vec4(v1 - v0, 0.0f);
    tri.e2 = glm::vec4(v2 - v0, 0.0f);
  }
}

void MeshBvh::refit(std::span<const glm::vec3> positions) {
  if (positions.size() != positions_.size())
    throw InputError(fmt::format("mesh BVH refit: {} vertices given, the mesh was built with {}",
                                 positions.size(), positions_.size()));
  check_positions(positions, "mesh BVH refit");
  positions_.assign(positions.begin(), positions.end());
  std::vector<Aabb> slot_bounds(order_.size());
  set_triangles(positions, slot_bounds);
  refit_bvh(nodes_, slot_bounds);
}

Aabb MeshBvh::bounds() const {
  return nodes_.empty() ? Aabb{} : node_bounds(nodes_[0]);
}

}  // namespace lantern::lighting
