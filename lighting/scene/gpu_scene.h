// scene.upload for a static level: device buffers holding SceneData (vertices, indices,
// materials, instances, BVH arrays, lights and their alias table), bound by the names the shaders
// use (bind()). Never-empty buffers: an empty array is uploaded as one zeroed element.
#pragma once

#include <cstdint>

#include "lighting/scene/scene_data.h"
#include "runtime/gpu/bindings.h"
#include "runtime/gpu/buffer.h"

namespace lantern::runtime {
class Device;
}

namespace lantern::lighting {

class GpuScene {
 public:
  GpuScene(runtime::Device& device, const SceneData& scene);

  // Binds every scene buffer by its shader name: bvh_header/BvhNodeBuffer..., scene_vertices,
  // scene_indices, scene_materials, scene_instances, scene_lights, light_alias.
  void bind(runtime::Bindings& bindings) const;

  std::uint32_t light_count() const { return light_count_; }
  std::uint32_t instance_count() const { return instance_count_; }
  float scene_radius() const { return scene_radius_; }
  std::uint64_t bytes() const;

 private:
  runtime::Buffer bvh_header_;
  runtime::Buffer bvh_nodes_;
  runtime::Buffer bvh_triangles_;
  runtime::Buffer bvh_instances_;
  runtime::Buffer vertices_;
  runtime::Buffer indices_;
  runtime::Buffer materials_;
  runtime::Buffer instances_;
  runtime::Buffer lights_;
  runtime::Buffer alias_;
  std::uint32_t light_count_ = 0;
  std::uint32_t instance_count_ = 0;
  float scene_radius_ = 1.0f;
};

}  // namespace lantern::lighting
