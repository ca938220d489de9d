// Two-level visibility structure: per-mesh BLASes (MeshBvh) under a TLAS over placed instances,
// packed into the GPU arrays of shaders/shared/bvh.h, with CPU queries that run the same traversal
// code as the GPU (shaders/shared/bvh_traverse.h).
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
};

class SceneBvh {
 public:
  // tlas_options.max_leaf_size is forced to 1: TLAS leaves reference one instance directly.
  explicit SceneBvh(const BvhBuildOptions& tlas_options = {});

  // Adds a mesh's BLAS; returns its id. Invalidates the TLAS until the next set_instances.
  std::uint32_t add_mesh(MeshBvh mesh);
  // Refits mesh `id` to moved vertices (see MeshBvh::refit) and updates its packed nodes and
  // triangles in place. Call set_instances afterwards: instance boxes depend on the mesh box.
  void refit_mesh(std::uint32_t id, std::span<const glm::vec3> positions);
  const MeshBvh& mesh(std::uint32_t id) const { return meshes_.at(id); }
  std::size_t mesh_count() const { return meshes_.size(); }

  // Places the instances and rebuilds the TLAS (cheap: meant to run every frame). Instances of
  // empty meshes stay in the instance array but are not in the TLAS. Throws lantern::InputError on
  // an unknown mesh id or a non-invertible / non-finite transform.
  void set_instances(std::span<const BvhInstanceDesc> instances);

  // Packed GPU arrays: all BLAS nodes (mesh by mesh), then the TLAS; triangles mesh by mesh.
  const gpu::BvhSceneHeader& header() const { return header_; }
  const std::vector<gpu::BvhNode>& nodes() const { return nodes_; }
  const std::vector<gpu::BvhTriangle>& triangles() const { return triangles_; }
  const std::vector<gpu::BvhInstance>& instances() const { return instances_; }
  gpu::BvhSceneView view() const;
  // Mesh id of instance i (as given to set_instances): for other backends building their own
  // structures from the same scene (lighting/visibility/ray_query_scene.h).
  std::uint32_t instance_mesh(std::size_t i) const { return instance_meshes_.at(i); }

  // CPU queries (same code as the GPU). Rays are in world space.
  bool trace_closest(const gpu::BvhRay& ray, gpu::BvhHit& hit) const;
  bool trace_any(const gpu::BvhRay& ray) const;
  bool visible(const glm::vec3& origin, const glm::vec3& target) const;

 private:
  BvhBuildOptions tlas_options_;
  std::vector<MeshBvh> meshes_;
  std::vector<std::uint32_t> mesh_node_offset_;
  std::vector<std::uint32_t> mesh_triangle_offset_;
  std::uint32_t blas_node_count_ = 0;
  std::vector<gpu::BvhNode> nodes_;
  std::vector<gpu::BvhTriangle> triangles_;
  std::vector<gpu::BvhInstance> instances_;
  std::vector<std::uint32_t> instance_meshes_;
  gpu::BvhSceneHeader header_{};
};

}  // namespace lantern::lighting
