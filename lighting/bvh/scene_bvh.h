// Visibility structure: per-mesh BLASes (MeshBvh) under a TLAS over placed instances, except that
// instances declared fixed (they never move) are merged into one world-space tree, the TLAS's
// "fixed" leaf. Two levels cost the traversal every instance box a ray enters, and generated
// levels place meshes whose boxes overlap most of the scene (night_market: an average primary ray
// entered 21 instance boxes), so only what moves keeps its own instance. Packed into the GPU
// arrays of shaders/shared/bvh.h, with CPU queries that run the same traversal code as the GPU
// (shaders/shared/bvh_traverse.h). A merged triangle reports its own instance in hits.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <span>
#include <vector>

#include "lighting/bvh/mesh_bvh.h"
#include "shared/bvh_traverse.h"

namespace lantern::lighting {

struct BvhInstanceDesc {
  std::uint32_t mesh = 0;           // id returned by SceneBvh::add_mesh
  glm::mat4 object_to_world{1.0f};  // must be invertible (affine)
  std::uint32_t user_id = 0;        // returned in hits (e.g. the ECS entity)
  std::uint32_t flags = 0;          // gpu::kBvhInstance* (alpha-tested material)
  // The instance never moves (and its mesh never deforms) and is not alpha-tested: its
  // triangles may join the one
  // world-space tree of fixed geometry. An instance declared fixed that later moves is taken
  // out of that tree by the set_instances that sees it move (a rebuild of the tree: slow, once).
  bool fixed = false;
};

// Fixed instances are merged while the merged tree stays within this many triangles or twice the
// scene's distinct triangles, whichever is larger (a mesh placed many times is left instanced
// rather than copied without bound).
inline constexpr std::size_t kBvhMergedTriangleFloor = std::size_t{1} << 20;

class SceneBvh {
 public:
  // tlas_options.max_leaf_size is forced to 1: TLAS leaves reference one instance directly.
  explicit SceneBvh(const BvhBuildOptions& tlas_options = {});

  // Adds a mesh's BLAS; returns its id. The packed arrays are valid after the next set_instances.
  std::uint32_t add_mesh(MeshBvh mesh);
  // Refits mesh `id` to moved vertices (see MeshBvh::refit) and updates its packed nodes and
  // triangles in place; its instances are never merged from then on. Call set_instances
  // afterwards: instance boxes (and the merged tree) depend on the mesh.
  void refit_mesh(std::uint32_t id, std::span<const glm::vec3> positions);
  const MeshBvh& mesh(std::uint32_t id) const { return meshes_.at(id); }
  std::size_t mesh_count() const { return meshes_.size(); }

  // Places the instances and rebuilds the TLAS (cheap: meant to run every frame while the fixed
  // instances stay where they were). Instances of empty meshes and merged instances stay in the
  // instance array but are not TLAS leaves. Throws lantern::InputError on an unknown mesh id or a
  // non-invertible / non-finite transform.
  void set_instances(std::span<const BvhInstanceDesc> instances);

  // Packed GPU arrays: the BLAS nodes of every mesh a TLAS leaf uses (mesh by mesh), the merged
  // tree, then the TLAS; triangles likewise. instances(): one record per instance given to
  // set_instances, in order, then (when any instance was merged) the merged tree's record.
  const gpu::BvhSceneHeader& header() const { return header_; }
  const std::vector<gpu::BvhNode>& nodes() const { return nodes_; }
  const std::vector<gpu::BvhTriangle>& triangles() const { return triangles_; }
  const std::vector<gpu::BvhInstance>& instances() const { return instances_; }
  gpu::BvhSceneView view() const;
  // Instances given to the last set_instances (instances() may hold one more record).
  std::size_t instance_count() const { return instance_meshes_.size(); }
  // Mesh id of instance i (as given to set_instances): for other backends building their own
  // structures from the same scene (lighting/visibility/ray_query_scene.h).
  std::uint32_t instance_mesh(std::size_t i) const { return instance_meshes_.at(i); }
  // Whether instance i (as given to the last set_instances) is in the merged tree: for other
  // backends that mirror the layout (lighting/visibility/host_visibility.h).
  bool merged(std::size_t i) const { return i < is_merged_.size() && is_merged_[i]; }
  // Instances merged into the fixed tree, and its triangle count.
  std::size_t merged_instance_count() const { return merged_.size(); }
  std::size_t merged_triangle_count() const { return merged_triangles_.size(); }
  // Changes whenever the BLAS part of the packed arrays (everything before the TLAS) changed, so
  // an uploader knows when a TLAS-only update is not enough.
  std::uint64_t blas_generation() const { return blas_generation_; }

  // CPU queries (same code as the GPU). Rays are in world space.
  bool trace_closest(const gpu::BvhRay& ray, gpu::BvhHit& hit) const;
  bool trace_any(const gpu::BvhRay& ray) const;
  bool visible(const glm::vec3& origin, const glm::vec3& target) const;

 private:
  struct Merged {
    std::uint32_t instance;
    std::uint32_t mesh;
    glm::mat4 object_to_world;
    bool operator==(const Merged&) const = default;
  };
  // Which fixed instances join the merged tree (in instance order, within the triangle cap).
  // Marks merged instances that moved or changed mesh (moved_fixed_: never merged again).
  std::vector<Merged> choose_merged(std::span<const BvhInstanceDesc> instances);
  void build_merged_tree(std::span<const BvhInstanceDesc> instances);
  // Repacks nodes_/triangles_: BLASes of the meshes TLAS leaves use, then the merged tree.
  void pack_blases(std::span<const BvhInstanceDesc> instances);

  BvhBuildOptions tlas_options_;
  std::vector<MeshBvh> meshes_;
  std::vector<bool> mesh_deforms_;  // refit at least once: never merged
  std::vector<std::uint32_t> mesh_node_offset_;      // kNotPacked for meshes no TLAS leaf uses
  std::vector<std::uint32_t> mesh_triangle_offset_;
  std::vector<Merged> merged_;
  std::vector<bool> is_merged_;    // per instance of the last set_instances
  std::vector<bool> moved_fixed_;  // declared fixed, then moved
  std::vector<gpu::BvhNode> merged_nodes_;
  std::vector<gpu::BvhTriangle> merged_triangles_;  // world space; e1.w = source instance + 1
  std::uint32_t merged_node_offset_ = 0;
  std::uint32_t merged_triangle_offset_ = 0;
  bool packed_ = false;
  std::uint64_t blas_generation_ = 0;
  std::uint32_t blas_node_count_ = 0;
  std::vector<gpu::BvhNode> nodes_;
  std::vector<gpu::BvhTriangle> triangles_;
  std::vector<gpu::BvhInstance> instances_;
  std::vector<std::uint32_t> instance_meshes_;
  gpu::BvhSceneHeader header_{};
};

}  // namespace lantern::lighting
