// FrameRenderer: scene.upload -> gbuffer -> integrator passes (frame_renderer.h).
#include "lighting/frame/frame_renderer.h"

#include <fmt/format.h>

#include "engine/core/error.h"
#include "engine/core/log.h"
#include "lighting/frame/frame_output_pass.h"
#include "lighting/gbuffer/gbuffer_pass.h"
#include "lighting/scene/frame_constants.h"
#include "runtime/core/device.h"
#include "runtime/gpu/compute_pipeline.h"
#include "runtime/gpu/shader_library.h"

namespace lantern::lighting {

FrameRenderer::FrameRenderer(runtime::Device& device, runtime::ShaderLibrary& shaders,
                             std::shared_ptr<const Level> level,
                             std::unique_ptr<Integrator> integrator, std::uint32_t width,
                             std::uint32_t height, std::uint32_t seed)
    : device_(device),
      integrator_(std::move(integrator)),
      width_(width),
      height_(height),
      seed_(seed) {
  if (width == 0 || height == 0) {
    throw InputError(
        fmt::format("frame renderer: render size {}x{} must be positive", width, height));
  }
  if (!integrator_) throw InputError("frame renderer: no integrator");
  scene_ = std::make_unique<GpuScene>(device, std::move(level), integrator_->visibility());
  gbuffer_ = std::make_unique<GBufferPass>(
      device, shaders, GBufferPassOptions{.textured = !scene_->data().textures.empty()});
  output_ = std::make_unique<runtime::ComputePipeline>(
      device, shaders.load("frame/frame_output.comp"),
      runtime::ComputePipelineDesc{.name = "frame.output", .constants = {}});
  log::debug(
      "scene '{}': {} instances, {} BVH triangles, {} lights ({} emissive triangles), "
      "{:.1f} MiB",
      scene_->level().name, scene_->instance_count(), scene_->data().bvh.triangles().size(),
      scene_->light_record_count(), scene_->emissive_triangles(),
      static_cast<double>(scene_->bytes()) / (1024.0 * 1024.0));
}

FrameRenderer::~FrameRenderer() = default;

void FrameRenderer::warm_up() {
  gbuffer_->warm_up();
  integrator_->warm_up();
  output_->warm_up();
}

void FrameRenderer::resize(std::uint32_t width, std::uint32_t height) {
  if (width == 0 || height == 0) {
    throw InputError(
        fmt::format("frame renderer: render size {}x{} must be positive", width, height));
  }
  if (width == width_ && height == height_) return;
  width_ = width;
  height_ = height;
  resized_ = true;
}

runtime::graph::BufferHandle FrameRenderer::add_frame(runtime::graph::RenderGraph& graph,
                                                      const FrameSnapshot& snapshot) {
  const bool history_valid = frames_ > 0 && !snapshot.camera_cut && !resized_;
  scene_->update(snapshot);
  const FrameCounts counts{scene_->light_count(), scene_->instance_count(),
                           scene_->emissive_triangles(), scene_->previous_light_count(),
                           scene_->scene_radius()};
  scene_->set_frame_constants(
      make_frame_constants(snapshot, width_, height_, frames_, seed_, counts, history_valid));
  // The one decision on history: the graph drops it; every pass then sees invalid history handles.
  if (!history_valid) graph.invalidate_history();
  history_valid_ = history_valid;

  const SceneHandles scene = scene_->add_upload_pass(graph, scene_->import(graph));
  const GBufferHandles gbuffer =
      gbuffer_->add_pass(graph, scene, *scene_, width_, height_, scene_->instance_count());
  runtime::graph::BufferHandle hdr =
      graph.create_buffer("frame.hdr", {VkDeviceSize{width_} * height_ * 4 * sizeof(float)});

  inputs_ = {};
  inputs_.snapshot = &snapshot;
  inputs_.scene = scene_.get();
  inputs_.scene_handles = scene;
  inputs_.gbuffer = gbuffer;
  inputs_.width = width_;
  inputs_.height = height_;
  inputs_.frame_index = frames_;
  inputs_.seed = seed_;
  inputs_.light_count = scene_->light_count();
  inputs_.previous_light_count = scene_->previous_light_count();
  hdr = integrator_->add_passes(graph, inputs_, hdr);
  ++frames_;
  resized_ = false;
  return hdr;
}

runtime::graph::ImageHandle FrameRenderer::add_output_pass(runtime::graph::RenderGraph& graph,
                                                           runtime::graph::BufferHandle hdr,
                                                           runtime::graph::ImageHandle target,
                                                           float exposure) {
  return add_frame_output_pass(graph, *output_, hdr, target, width_, height_, exposure);
}

}  // namespace lantern::lighting
