// Two-level BVH: packs BLASes into shared node/triangle arrays, rebuilds the TLAS over instance
// world boxes, and answers CPU ray queries through the shared traversal.
#include "lighting/bvh/scene_bvh.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "engine/core/error.h"

namespace lantern::lighting {
namespace {

bool finite(const glm::mat4& m) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!std::isfinite(m[c][r])) return false;
  return true;
}

}  // namespace

SceneBvh::SceneBvh(const BvhBuildOptions& tlas_options) : tlas_options_(tlas_options) {
  tlas_options_.max_leaf_size = 1;
}

std::uint32_t SceneBvh::add_mesh(MeshBvh mesh) {
  const auto id = static_cast<std::uint32_t>(meshes_.size());
  nodes_.resize(blas_node_count_);  // drop the TLAS: it follows the BLAS nodes
  header_.tlas_node_offset = blas_node_count_;
  header_.tlas_node_count = 0;
  mesh_node_offset_.push_back(blas_node_count_);
  mesh_triangle_offset_.push_back(static_cast<std::uint32_t>(triangles_.size()));
  nodes_.insert(nodes_.end(), mesh.nodes().begin(), mesh.nodes().end());
  triangles_.insert(triangles_.end(), mesh.triangles().begin(), mesh.triangles().end());
  blas_node_count_ = static_cast<std::uint32_t>(nodes_.size());
  header_.tlas_node_offset = blas_node_count_;
  header_.triangle_count = static_cast<std::uint32_t>(triangles_.size());
  meshes_.push_back(std::move(mesh));
  return id;
}

void SceneBvh::refit_mesh(std::uint32_t id, std::span<const glm::vec3> positions) {
  if (id >= meshes_.size())
    throw InputError(
        fmt::format("scene BVH refit: unknown mesh id {} ({} meshes)", id, meshes_.size()));
  MeshBvh& mesh = meshes_[id];
  mesh.refit(positions);
  std::copy(mesh.nodes().begin(), mesh.nodes().end(), nodes_.begin() + mesh_node_offset_[id]);
  std::copy(mesh.triangles().begin(), mesh.triangles().end(),
            triangles_.begin() + mesh_triangle_offset_[id]);
}

void SceneBvh::set_instances(std::span<const BvhInstanceDesc> instances) {
  instances_.clear();
  instances_.reserve(instances.size());
  instance_meshes_.clear();
  instance_meshes_.reserve(instances.size());
  std::vector<Aabb> world_bounds;
  std::vector<std::uint32_t> placed;  // indices of instances that go into the TLAS
  for (std::size_t i = 0; i < instances.size(); ++i) {
    const BvhInstanceDesc& desc = instances[i];
    if (desc.mesh >= meshes_.size())
      throw InputError(fmt::format("scene BVH: instance {} uses unknown mesh id {} ({} meshes)", i,
                                   desc.mesh, meshes_.size()));
    const glm::mat4 inverse = glm::inverse(desc.object_to_world);
    if (!finite(desc.object_to_world) || !finite(inverse) ||
        glm::determinant(desc.object_to_world) == 0.0f)
      throw InputError(
          fmt::format("scene BVH: instance {} has a non-finite or singular transform", i));
    gpu::BvhInstance inst{};
    inst.object_to_world = desc.object_to_world;
    inst.world_to_object = inverse;
    inst.node_offset = mesh_node_offset_[desc.mesh];
    inst.triangle_offset = mesh_triangle_offset_[desc.mesh];
    inst.user_id = desc.user_id;
    inst.flags = desc.flags;
    instances_.push_back(inst);
    instance_meshes_.push_back(desc.mesh);
    const MeshBvh& mesh = meshes_[desc.mesh];
    if (mesh.empty()) continue;
    world_bounds.push_back(mesh.bounds().transformed(desc.object_to_world));
    placed.push_back(static_cast<std::uint32_t>(i));
  }

  BvhBuildOutput tlas = build_bvh(world_bounds, tlas_options_);
  // Leaves hold one primitive: point them straight at the instance.
  for (gpu::BvhNode& node : tlas.nodes) {
    if (gpu::bvh_node_is_leaf(node))
      node.bounds_min.w =
          glm::uintBitsToFloat(placed[tlas.primitive_order[gpu::bvh_node_index(node)]]);
  }
  nodes_.resize(blas_node_count_);
  nodes_.insert(nodes_.end(), tlas.nodes.begin(), tlas.nodes.end());
  header_.tlas_node_offset = blas_node_count_;
  header_.tlas_node_count = static_cast<std::uint32_t>(tlas.nodes.size());
  header_.instance_count = static_cast<std::uint32_t>(instances_.size());
}

gpu::BvhSceneView SceneBvh::view() const {
  gpu::BvhSceneView v;
  v.nodes = nodes_.data();
  v.triangles = triangles_.data();
  v.instances = instances_.data();
  v.header = header_;
  return v;
}

bool SceneBvh::trace_closest(const gpu::BvhRay& ray, gpu::BvhHit& hit) const {
  return gpu::bvh_trace_closest(view(), ray, hit);
}

bool SceneBvh::trace_any(const gpu::BvhRay& ray) const {
  return gpu::bvh_trace_any(view(), ray);
}

bool SceneBvh::visible(const glm::vec3& origin, const glm::vec3& target) const {
  return gpu::bvh_visible(view(), origin, target);
}

}  // namespace lantern::lighting
