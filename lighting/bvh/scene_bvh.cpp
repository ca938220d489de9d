// Scene BVH: merges fixed instances into one world-space tree, packs it and the BLASes the TLAS
// uses into shared node/triangle arrays, rebuilds the TLAS over instance world boxes, and answers
// CPU ray queries through the shared traversal.
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

constexpr std::uint32_t kNotPacked = ~0u;

SceneBvh::SceneBvh(const BvhBuildOptions& tlas_options) : tlas_options_(tlas_options) {
  tlas_options_.max_leaf_size = 1;
}

std::uint32_t SceneBvh::add_mesh(MeshBvh mesh) {
  const auto id = static_cast<std::uint32_t>(meshes_.size());
  meshes_.push_back(std::move(mesh));
  mesh_deforms_.push_back(false);
  mesh_node_offset_.push_back(kNotPacked);
  mesh_triangle_offset_.push_back(kNotPacked);
  packed_ = false;  // set_instances packs it (if a TLAS leaf uses it)
  nodes_.resize(blas_node_count_);  // drop the TLAS until the next set_instances
  header_.tlas_node_count = 0;
  return id;
}

void SceneBvh::refit_mesh(std::uint32_t id, std::span<const glm::vec3> positions) {
  if (id >= meshes_.size())
    throw InputError(
        fmt::format("scene BVH refit: unknown mesh id {} ({} meshes)", id, meshes_.size()));
  MeshBvh& mesh = meshes_[id];
  mesh.refit(positions);
  mesh_deforms_[id] = true;
  if (mesh_node_offset_[id] == kNotPacked) {
    packed_ = false;  // its instances leave the merged tree at the next set_instances
    return;
  }
  std::copy(mesh.nodes().begin(), mesh.nodes().end(), nodes_.begin() + mesh_node_offset_[id]);
  std::copy(mesh.triangles().begin(), mesh.triangles().end(),
            triangles_.begin() + mesh_triangle_offset_[id]);
}

std::vector<SceneBvh::Merged> SceneBvh::choose_merged(
    std::span<const BvhInstanceDesc> instances) {
  moved_fixed_.resize(instances.size(), false);
  for (const Merged& m : merged_) {
    if (m.instance >= instances.size()) continue;
    const BvhInstanceDesc& now = instances[m.instance];
    if (now.object_to_world != m.object_to_world || now.mesh != m.mesh)
      moved_fixed_[m.instance] = true;
  }
  std::size_t distinct = 0;
  for (const MeshBvh& mesh : meshes_) distinct += mesh.triangle_count();
  const std::size_t cap = std::max(kBvhMergedTriangleFloor, 2 * distinct);
  std::vector<Merged> chosen;
  std::size_t total = 0;
  for (std::size_t i = 0; i < instances.size(); ++i) {
    const BvhInstanceDesc& desc = instances[i];
    if (!desc.fixed || desc.flags != 0 || moved_fixed_[i] || mesh_deforms_[desc.mesh]) continue;
    const std::size_t count = meshes_[desc.mesh].triangle_count();
    if (count == 0 || total + count > cap) continue;
    total += count;
    chosen.push_back({static_cast<std::uint32_t>(i), desc.mesh, desc.object_to_world});
  }
  return chosen;
}

void SceneBvh::build_merged_tree(std::span<const BvhInstanceDesc> instances) {
  merged_nodes_.clear();
  merged_triangles_.clear();
  if (merged_.empty()) return;
  // World-space vertices (each shared vertex transformed once: the merged mesh stays watertight).
  std::vector<glm::vec3> positions;
  std::vector<std::uint32_t> indices;
  std::vector<std::uint32_t> first_triangle;  // per merged instance, in the merged index space
  for (const Merged& m : merged_) {
    const MeshBvh& mesh = meshes_[instances[m.instance].mesh];
    const auto base = static_cast<std::uint32_t>(positions.size());
    first_triangle.push_back(static_cast<std::uint32_t>(indices.size() / 3));
    for (const glm::vec3& p : mesh.positions())
      positions.push_back(glm::vec3(m.object_to_world * glm::vec4(p, 1.0f)));
    for (std::uint32_t index : mesh.indices()) indices.push_back(base + index);
  }
  BvhBuildOptions options;
  options.thread_count = tlas_options_.thread_count;
  const MeshBvh tree(positions, indices, options);
  merged_nodes_ = tree.nodes();
  merged_triangles_ = tree.triangles();
  // v0.w: the triangle's index within its own mesh; e1.w: its instance + 1 (shared/bvh.h).
  for (gpu::BvhTriangle& tri : merged_triangles_) {
    const std::uint32_t t = glm::floatBitsToUint(tri.v0.w);
    const auto k = static_cast<std::size_t>(
        std::upper_bound(first_triangle.begin(), first_triangle.end(), t) -
        first_triangle.begin() - 1);
    tri.v0.w = glm::uintBitsToFloat(t - first_triangle[k]);
    tri.e1.w = glm::uintBitsToFloat(merged_[k].instance + 1u);
  }
}

void SceneBvh::pack_blases(std::span<const BvhInstanceDesc> instances) {
  std::vector<bool> used(meshes_.size(), false);
  for (std::size_t i = 0; i < instances.size(); ++i)
    if (!is_merged_[i]) used[instances[i].mesh] = true;
  nodes_.clear();
  triangles_.clear();
  for (std::size_t m = 0; m < meshes_.size(); ++m) {
    mesh_node_offset_[m] = kNotPacked;
    mesh_triangle_offset_[m] = kNotPacked;
    if (!used[m]) continue;
    mesh_node_offset_[m] = static_cast<std::uint32_t>(nodes_.size());
    mesh_triangle_offset_[m] = static_cast<std::uint32_t>(triangles_.size());
    nodes_.insert(nodes_.end(), meshes_[m].nodes().begin(), meshes_[m].nodes().end());
    triangles_.insert(triangles_.end(), meshes_[m].triangles().begin(),
                      meshes_[m].triangles().end());
  }
  merged_node_offset_ = static_cast<std::uint32_t>(nodes_.size());
  merged_triangle_offset_ = static_cast<std::uint32_t>(triangles_.size());
  nodes_.insert(nodes_.end(), merged_nodes_.begin(), merged_nodes_.end());
  triangles_.insert(triangles_.end(), merged_triangles_.begin(), merged_triangles_.end());
  blas_node_count_ = static_cast<std::uint32_t>(nodes_.size());
  header_.triangle_count = static_cast<std::uint32_t>(triangles_.size());
  packed_ = true;
  ++blas_generation_;
}

void SceneBvh::set_instances(std::span<const BvhInstanceDesc> instances) {
  std::vector<glm::mat4> inverses;
  inverses.reserve(instances.size());
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
    inverses.push_back(inverse);
  }

  std::vector<Merged> chosen = choose_merged(instances);
  const bool merged_changed = chosen != merged_;
  if (merged_changed) {
    merged_ = std::move(chosen);
    build_merged_tree(instances);
  }
  is_merged_.assign(instances.size(), false);
  for (const Merged& m : merged_) is_merged_[m.instance] = true;
  bool repack = !packed_ || merged_changed;
  for (std::size_t i = 0; i < instances.size() && !repack; ++i)
    repack = !is_merged_[i] && mesh_node_offset_[instances[i].mesh] == kNotPacked;
  if (repack) pack_blases(instances);

  instances_.clear();
  instances_.reserve(instances.size() + 1);
  instance_meshes_.clear();
  instance_meshes_.reserve(instances.size());
  std::vector<Aabb> world_bounds;
  std::vector<std::uint32_t> placed;  // indices of instances that are TLAS leaves
  for (std::size_t i = 0; i < instances.size(); ++i) {
    const BvhInstanceDesc& desc = instances[i];
    gpu::BvhInstance inst{};
    inst.object_to_world = desc.object_to_world;
    inst.world_to_object = inverses[i];
    // A merged instance's mesh may not be packed: nothing traverses it through this record.
    const bool packed = mesh_node_offset_[desc.mesh] != kNotPacked;
    inst.node_offset = packed ? mesh_node_offset_[desc.mesh] : 0u;
    inst.triangle_offset = packed ? mesh_triangle_offset_[desc.mesh] : 0u;
    inst.user_id = desc.user_id;
    inst.flags = desc.flags;
    instances_.push_back(inst);
    instance_meshes_.push_back(desc.mesh);
    const MeshBvh& mesh = meshes_[desc.mesh];
    if (mesh.empty() || is_merged_[i]) continue;
    world_bounds.push_back(mesh.bounds().transformed(desc.object_to_world));
    placed.push_back(static_cast<std::uint32_t>(i));
  }
  if (!merged_nodes_.empty()) {
    // The merged tree's record: identity transforms (its triangles are in world space).
    gpu::BvhInstance inst{};
    inst.object_to_world = glm::mat4(1.0f);
    inst.world_to_object = glm::mat4(1.0f);
    inst.node_offset = merged_node_offset_;
    inst.triangle_offset = merged_triangle_offset_;
    world_bounds.push_back(node_bounds(merged_nodes_[0]));
    placed.push_back(static_cast<std::uint32_t>(instances_.size()));
    instances_.push_back(inst);
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
