// gbuffer: rasterises the scene into the G-buffer of shaders/shared/gbuffer.h (world position +
// view depth, octahedral shading/geometric normals facing the camera, albedo/roughness,
// front-face emission/metallic, instance/material/primitive ids, motion in pixels) with one
// graphics pass and dynamic rendering; vertex pulling from the scene's storage buffers.
// Reads: scene frame_constants, vertices, indices, materials, instances (SceneHandles).
// Writes: the six colour images (transient, returned) and gbuffer.depth (transient, internal).
// History: none (motion comes from FrameConstants.prev_view_proj and
// GpuInstance.prev_object_to_world). Shape: `gbuffer.draws` (compute, one thread per instance)
// writes one VkDrawIndirectCommand per instance from the instance records, then `gbuffer` issues
// one non-indexed indirect draw per instance (no culling: two-sided geometry).
#pragma once

#include <cstdint>

#include "lighting/frame/frame_inputs.h"
#include "runtime/gpu/compute_pipeline.h"
#include "runtime/gpu/graphics_pipeline.h"
#include "runtime/graph/render_graph.h"

namespace lantern::runtime {
class Device;
class ShaderLibrary;
}  // namespace lantern::runtime

namespace lantern::lighting {

class GpuScene;

class GBufferPass {
 public:
  GBufferPass(runtime::Device& device, runtime::ShaderLibrary& shaders);

  // JIT-compiles both pipelines now (a 1x1 frame with one triangle through a private graph), so
  // the first timed frame does not pay lavapipe's compile.
  void warm_up();

  // Adds `gbuffer.draws` and `gbuffer` to `graph`; returns the G-buffer images they write.
  // `scene` must hold frame_constants (size width x height), vertices, indices, materials and
  // instances (instance_count records). Throws lantern::InputError for a zero size.
  [[nodiscard]] GBufferHandles add_pass(runtime::graph::RenderGraph& graph,
                                        const SceneHandles& scene, const GpuScene& gpu_scene,
                                        std::uint32_t width, std::uint32_t height,
                                        std::uint32_t instance_count);
  // The same without a GpuScene (the passes only need the handles): tests, benchmarks, warm-up.
  [[nodiscard]] GBufferHandles add_pass(runtime::graph::RenderGraph& graph,
                                        const SceneHandles& scene, std::uint32_t width,
                                        std::uint32_t height, std::uint32_t instance_count);

 private:
  runtime::Device& device_;
  runtime::ComputePipeline draws_;
  runtime::GraphicsPipeline raster_;
};

}  // namespace lantern::lighting
