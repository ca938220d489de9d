// The GPU side of scene visibility for every pass, whatever the backend: the compute BVH's arrays
// (always uploaded: storage buffers and rgba32ui texel views of the same memory) and, for the
// ray-query backend, the BLASes and TLAS (ray_query_scene.h). Integrators stay backend-agnostic:
//   #include "lib/visibility.glsl"                         // in the shader
//   shaders.load(path, visibility_variant(vis.backend()))  // pick the compiled variant
//   vis.bind(bindings);                                    // binds what that variant declares
// Per frame, after SceneBvh::set_instances: vis.update(bvh) (TLAS nodes + instances re-uploaded;
// the ray-query TLAS rebuilt). Both are blocking one-shot submits: this is the standalone form the
// visibility probe tests and visibility_bench use; the frame's scene (GpuScene) holds the same
// arrays as scene buffers and rebuilds the TLAS in its graph pass scene.tlas_build.
#pragma once

#include <cstdint>
#include <memory>

#include "lighting/visibility/visibility_backend.h"
#include "runtime/gpu/buffer.h"
#include "runtime/gpu/buffer_view.h"

namespace lantern::runtime {
class Bindings;
class Device;
}  // namespace lantern::runtime

namespace lantern::lighting {

class RayQueryScene;
class SceneBvh;

class VisibilityScene {
 public:
  // Throws lantern::InputError when RayQuery is asked of a device without it.
  VisibilityScene(runtime::Device& device, const SceneBvh& bvh, VisibilityBackend backend);
  ~VisibilityScene();
  VisibilityScene(VisibilityScene&&) noexcept;
  VisibilityScene& operator=(VisibilityScene&&) noexcept;

  VisibilityBackend backend() const { return backend_; }

  // Re-uploads what set_instances changed (header, nodes, instances; BLAS nodes/triangles too if
  // a mesh was refit) and rebuilds the ray-query TLAS. Blocking: call between frames, while no
  // submitted work reads these buffers.
  void update(const SceneBvh& bvh);

  // Binds the visibility resources the pipeline's shader declares (lib/visibility.glsl):
  // scene_tlas (ray query), the BVH texel views (bvh_node_texels, bvh_triangle_texels,
  // bvh_instance_texels) or the BVH storage buffers (BvhNodeBuffer, ...), and BvhHeaderBuffer.
  // Throws naming the binding when the shader wants the TLAS but the backend is the BVH.
  void bind(runtime::Bindings& bindings) const;

  const RayQueryScene* ray_query() const { return ray_query_.get(); }

 private:
  void upload_bvh(const SceneBvh& bvh);

  runtime::Device* device_;
  VisibilityBackend backend_;
  runtime::Buffer header_;
  runtime::Buffer nodes_;
  runtime::Buffer triangles_;
  runtime::Buffer instances_;
  runtime::BufferView node_view_;
  runtime::BufferView triangle_view_;
  runtime::BufferView instance_view_;
  std::unique_ptr<RayQueryScene> ray_query_;
};

}  // namespace lantern::lighting
