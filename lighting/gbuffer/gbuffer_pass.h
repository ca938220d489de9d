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
// Reads: scene frame_constants, vertices, indices, materials, instances (SceneHandles).
// Writes: the six colour images (transient, returned) and internal transients.
// History: none (motion comes from FrameConstants.prev_view_proj and
// GpuInstance.prev_object_to_world).
#pragma once

#include <cstdint>
#include <optional>
#include <span>

#include "lighting/frame/frame_inputs.h"
#include "runtime/gpu/compute_pipeline.h"
#include "runtime/gpu/graphics_pipeline.h"
#include "runtime/graph/render_graph.h"
#include "runtime/runtime_fwd.h"
#include "shared/scene.h"

namespace lantern::lighting {

class GpuScene;

// How the G-buffer is produced (the images and encodings are the same either way).
enum class GBufferMethod : std::uint8_t {
  // Per frame: Forward when the frame has at most one triangle per kForwardPixelsPerTriangle
  // pixels, else Visibility (the default).
  Auto,
  // Cull, raster the kept triangles' ids into gbuffer.visibility, resolve every image per pixel:
  // cost ~ triangles / cores + pixels. 4-5x faster than Forward on night_market at 320x180.
  Visibility,
  // One raster pass interpolating every attribute: cost ~ triangles (single-threaded front end,
  // every varying) + pixels (cheaper per pixel than the resolve: 1.8x faster on cornell_lights).
  Forward,
};

// Measured crossover (tests/gbuffer/gbuffer_bench.cpp on lavapipe): Forward costs ~0.35 us per
// triangle and ~40 ns per pixel, Visibility ~0.035 us per triangle (+ ~0.3 us per kept one) and
// ~60 ns per pixel, so Forward wins below roughly one triangle per 14 pixels.
inline constexpr std::uint64_t kForwardPixelsPerTriangle = 16;

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

  static std::uint64_t triangle_count(std::span<const gpu::GpuInstance> instances);
  // The method a frame of `triangles` at width x height uses (Auto resolved; others as given).
  static GBufferMethod method_for(GBufferMethod method, std::uint64_t triangles,
                                  std::uint32_t width, std::uint32_t height);

 private:
  GBufferHandles add_method(runtime::graph::RenderGraph& graph, const SceneHandles& scene,
                            std::uint32_t width, std::uint32_t height, std::uint32_t instance_count,
                            std::uint64_t triangles, GBufferMethod method);
  GBufferHandles add_visibility(runtime::graph::RenderGraph& graph, const SceneHandles& scene,
                                std::uint32_t width, std::uint32_t height,
                                std::uint32_t instance_count, std::uint32_t triangles);
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
  // Forward method.
  std::optional<runtime::ComputePipeline> forward_draws_;
  std::optional<runtime::GraphicsPipeline> forward_raster_;
};

}  // namespace lantern::lighting
