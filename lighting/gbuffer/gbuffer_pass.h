// gbuffer: rasterises the scene into the G-buffer of shaders/shared/gbuffer.h (world position +
// view depth, octahedral shading/geometric normals facing the camera, albedo/roughness,
// front-face emission/metallic, instance/material/primitive ids, motion in pixels).
// Visibility method (default): `gbuffer.draws` (one workgroup) lays out the per-instance work and
// indirect arguments from the instance records; `gbuffer.cull` (compute, one thread per triangle)
// keeps only triangles that can cover a pixel centre and writes their clip positions;
// `gbuffer` rasterises those (one indirect draw, flat list index only) into gbuffer.visibility +
// gbuffer.depth; `gbuffer.resolve` (full-screen raster) rebuilds every G-buffer image per pixel
// from the triangle (ray/triangle barycentrics at the pixel centre). lavapipe's raster front end
// is single-threaded and pays per triangle and per varying; culling runs on every core.
// Forward method: `gbuffer.draws` + `gbuffer`, one draw per instance interpolating every
// attribute; cheaper per pixel, so Auto (the default) picks it for frames with few triangles per
// pixel (kForwardPixelsPerTriangle).
// Host method (CPU devices with host visibility): `gbuffer.host`, a host pass, traces each
// pixel's camera ray with Embree (HostVisibility::trace_primary) into gbuffer.host_hits, and
// `gbuffer.resolve` (its "hosthits" variant) rebuilds the images from those (instance, triangle)
// records: no triangle is culled or rasterised, so the cost follows the pixels, not the
// triangles (log of them). Auto picks it over Visibility on a CPU device whose scene has host
// visibility, from kHostTrianglesPerPixel triangles per pixel up.
// Reads: scene frame_constants, vertices, indices, materials, instances (SceneHandles).
// Writes: the six colour images (transient, returned) and internal transients.
// History: none (motion comes from FrameConstants.prev_view_proj and
// GpuInstance.prev_object_to_world).
#pragma once

#include <cstdint>
#include <optional>
#include <span>

#include "lighting/frame/frame_inputs.h"
#include "lighting/gbuffer/gbuffer_method.h"
#include "runtime/gpu/compute_pipeline.h"
#include "runtime/gpu/graphics_pipeline.h"
#include "runtime/graph/render_graph.h"
#include "runtime/runtime_fwd.h"
#include "shared/scene.h"

namespace lantern::lighting {

class GpuScene;
class HostVisibility;

// Measured crossover (tests/gbuffer/gbuffer_bench.cpp on lavapipe): Forward costs ~0.35 us per
// triangle and ~40 ns per pixel, Visibility ~0.035 us per triangle (+ ~0.3 us per kept one) and
// ~60 ns per pixel, so Forward wins below roughly one triangle per 14 pixels.
inline constexpr std::uint64_t kForwardPixelsPerTriangle = 16;
// Host vs Visibility (night_market, `lantern bench --set gbuffer=...` alternating, README): the
// host traces ~55-75 ns per pixel on two threads whatever the triangle count; at 320x180 (2.6
// triangles per pixel) it took 0.6-0.95x the cull + raster, at 640x360 (0.64) 1.05-1.15x. So
// Auto takes it from one triangle per pixel up.
inline constexpr std::uint64_t kHostTrianglesPerPixel = 1;

struct GBufferPassOptions {
  GBufferMethod method = GBufferMethod::Auto;
  // The scene has material textures (GpuScene::textured()): compiles the texture sampling and
  // alpha-cutout path into the fragment stages (specialisation constant kTextured); without, the
  // pipelines are the untextured ones.
  bool textured = false;
};

class GBufferPass {
 public:
  GBufferPass(runtime::Device& device, runtime::ShaderLibrary& shaders,
              const GBufferPassOptions& options = {});

  // JIT-compiles the method's pipelines now (a 1x1 frame with one triangle through a private
  // graph), so the first timed frame does not pay lavapipe's compile.
  void warm_up();

  // Adds the passes to `graph`; returns the G-buffer images they write. `scene` must hold
  // frame_constants (size width x height), vertices, indices, materials and instances (at least
  // instance_count records; the first instance_count are drawn). Throws lantern::InputError for a
  // zero size.
  [[nodiscard]] GBufferHandles add_pass(runtime::graph::RenderGraph& graph,
                                        const SceneHandles& scene, const GpuScene& gpu_scene,
                                        std::uint32_t width, std::uint32_t height,
                                        std::uint32_t instance_count);
  // The same without a GpuScene: `instances` are host copies of the records the device buffer
  // holds (only their triangle counts are used, to size the cull lists): tests, benchmarks.
  [[nodiscard]] GBufferHandles add_pass(runtime::graph::RenderGraph& graph,
                                        const SceneHandles& scene, std::uint32_t width,
                                        std::uint32_t height,
                                        std::span<const gpu::GpuInstance> instances);
  // The same with the instance count and the sum of their triangles (geometry.z / 3) given.
  [[nodiscard]] GBufferHandles add_pass(runtime::graph::RenderGraph& graph,
                                        const SceneHandles& scene, std::uint32_t width,
                                        std::uint32_t height, std::uint32_t instance_count,
                                        std::uint64_t triangles);

  // The host method's passes with `host` (the scene's Embree) tracing the camera of `frame`
  // (the constants `scene` holds this frame): what add_pass with a GpuScene adds when the method
  // is Host; tests and benchmarks call it directly.
  [[nodiscard]] GBufferHandles add_host_pass(runtime::graph::RenderGraph& graph,
                                             const SceneHandles& scene, std::uint32_t width,
                                             std::uint32_t height, HostVisibility& host,
                                             const gpu::FrameConstants& frame);

  // From now on frames use `method` (Auto: per frame, method_for). InputError when this pass was
  // made for another fixed method (GBufferPassOptions::method), whose pipelines it lacks.
  void set_method(GBufferMethod method);
  GBufferMethod method() const { return options_.method; }

  static std::uint64_t triangle_count(std::span<const gpu::GpuInstance> instances);
  // The method a frame of `triangles` at width x height uses (Auto resolved; others as given):
  // Forward for few triangles per pixel (kForwardPixelsPerTriangle), Host for many
  // (kHostTrianglesPerPixel) where `host` (the scene has host visibility on a CPU device: the
  // frame and `lantern info` decide it alike), else Visibility.
  static GBufferMethod method_for(GBufferMethod method, std::uint64_t triangles,
                                  std::uint32_t width, std::uint32_t height, bool host = false);

 private:
  GBufferHandles add_method(runtime::graph::RenderGraph& graph, const SceneHandles& scene,
                            std::uint32_t width, std::uint32_t height, std::uint32_t instance_count,
                            std::uint64_t triangles, GBufferMethod method);
  GBufferHandles add_visibility(runtime::graph::RenderGraph& graph, const SceneHandles& scene,
                                std::uint32_t width, std::uint32_t height,
                                std::uint32_t instance_count, std::uint32_t triangles);
  GBufferHandles resolve(runtime::graph::RenderGraph& graph, const SceneHandles& scene,
                         std::uint32_t width, std::uint32_t height,
                         runtime::graph::BufferHandle triangles,
                         runtime::graph::ImageHandle visibility);
  GBufferHandles add_forward(runtime::graph::RenderGraph& graph, const SceneHandles& scene,
                             std::uint32_t width, std::uint32_t height,
                             std::uint32_t instance_count);

  runtime::Device& device_;
  GBufferPassOptions options_;
  // Visibility method.
  std::optional<runtime::ComputePipeline> draws_;
  std::optional<runtime::ComputePipeline> cull_;
  std::optional<runtime::GraphicsPipeline> raster_;
  std::optional<runtime::GraphicsPipeline> resolve_;
  // Host method: the resolve reading one gbuffer.host_hits record per pixel.
  std::optional<runtime::GraphicsPipeline> resolve_hits_;
  // Forward method.
  std::optional<runtime::ComputePipeline> forward_draws_;
  std::optional<runtime::GraphicsPipeline> forward_raster_;
};

}  // namespace lantern::lighting
