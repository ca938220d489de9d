// FrameRenderer: scene.upload -> gbuffer -> integrator passes (frame_renderer.h).
#include "lighting/frame/frame_renderer.h"

#include <fmt/format.h>

#include <algorithm>

#include "engine/core/error.h"
#include "engine/core/log.h"
#include "lighting/denoise/denoiser.h"
#include "lighting/frame/frame_output_pass.h"
#include "lighting/gbuffer/gbuffer_pass.h"
#include "lighting/scene/frame_constants.h"
#include "lighting/upscale/upscaler.h"
#include "runtime/core/device.h"
#include "runtime/gpu/compute_pipeline.h"
#include "runtime/gpu/shader_library.h"
#include "lighting/volume/volume_camera_pass.h"

namespace lantern::lighting {

namespace {

// Radical inverse of `index` in `base`: the Halton sequence's coordinate.
float halton(std::uint32_t index, std::uint32_t base) {
  float f = 1.0f, r = 0.0f;
  for (; index > 0; index /= base) {
    f /= static_cast<float>(base);
    r += f * static_cast<float>(index % base);
  }
  return r;
}

// Sub-pixel offsets of the G-buffer samples: Halton (2, 3) points 1..8, centred on the pixel.
constexpr std::uint32_t kJitterPhases = 8;

}  // namespace

glm::vec2 FrameRenderer::jitter_sequence(std::uint32_t frame) {
  return glm::vec2(halton(frame % kJitterPhases + 1, 2), halton(frame % kJitterPhases + 1, 3)) -
         0.5f;
}

FrameOutput parse_frame_output(std::string_view text) {
  if (text == "raw") return FrameOutput::Raw;
  if (text == "denoised") return FrameOutput::Denoised;
  throw InputError(fmt::format("--output {}: expected raw or denoised", text));
}

const char* frame_output_name(FrameOutput output) {
  return output == FrameOutput::Denoised ? "denoised" : "raw";
}

FrameRenderer::FrameRenderer(runtime::Device& device, runtime::ShaderLibrary& shaders,
                             std::shared_ptr<const Level> level,
                             std::unique_ptr<Integrator> integrator, std::uint32_t width,
                             std::uint32_t height, std::uint32_t seed)
    : integrator_(std::move(integrator)),
      width_(width),
      height_(height),
      output_width_(width),
      output_height_(height),
      seed_(seed) {
  if (width == 0 || height == 0) {
    throw InputError(
        fmt::format("frame renderer: render size {}x{} must be positive", width, height));
  }
  if (!integrator_) throw InputError("frame renderer: no integrator");
  scene_ = std::make_unique<GpuScene>(device, std::move(level), integrator_->visibility());
  gbuffer_ = std::make_unique<GBufferPass>(
      device, shaders, GBufferPassOptions{.textured = !scene_->data().textures.empty()});
  denoiser_ = std::make_unique<Denoiser>(device, shaders);
  upscaler_ = std::make_unique<Upscaler>(device, shaders);
  integrator_->prepare(*scene_);
  if (scene_->volume_count() > 0 && !integrator_->renders_media()) {
    volume_camera_ =
        std::make_unique<VolumeCameraPass>(device, shaders, integrator_->visibility());
  }
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

void FrameRenderer::set_gbuffer_method(GBufferMethod method) { gbuffer_->set_method(method); }

void FrameRenderer::warm_up() {
  gbuffer_->warm_up();
  integrator_->warm_up();
  denoiser_->warm_up();
  upscaler_->warm_up();
  if (volume_camera_) volume_camera_->warm_up();
  output_->warm_up();
}

void FrameRenderer::resize(std::uint32_t width, std::uint32_t height) {
  if (width == 0 || height == 0) {
    throw InputError(
        fmt::format("frame renderer: render size {}x{} must be positive", width, height));
  }
  if (width == output_width_ && height == output_height_ && width == width_ &&
      height == height_) {
    return;
  }
  output_width_ = width;
  output_height_ = height;
  width_ = width;
  height_ = height;
  resized_ = true;
}

void FrameRenderer::set_internal_size(std::uint32_t width, std::uint32_t height) {
  width = std::clamp(width, 1u, output_width_);
  height = std::clamp(height, 1u, output_height_);
  if (width == width_ && height == height_) return;
  width_ = width;
  height_ = height;
  resized_ = true;
}

runtime::graph::BufferHandle FrameRenderer::add_frame(runtime::graph::RenderGraph& graph,
                                                      const FrameSnapshot& snapshot) {
  const bool history_valid = frames_ > 0 && !snapshot.camera_cut && !resized_;
  scene_->update(snapshot);
  const FrameCounts counts{scene_->light_count(),
                           scene_->instance_count(),
                           scene_->emissive_triangles(),
                           scene_->previous_light_count(),
                           scene_->scene_radius(),
                           scene_->volume_count(),
                           scene_->data().lights.first_group_share(),
                           scene_->light_remap_is_identity()};
  const bool upscaling = width_ != output_width_ || height_ != output_height_;
  const bool jitter = jitter_mode_ == Jitter::On || (jitter_mode_ == Jitter::WhenUpscaling && upscaling);
  previous_jitter_ = history_valid ? jitter_ : glm::vec2(0.0f);
  jitter_ = jitter ? jitter_sequence(frames_) : glm::vec2(0.0f);
  if (!history_valid) previous_jitter_ = jitter_;
  gpu::FrameConstants constants =
      make_frame_constants(snapshot, width_, height_, frames_, seed_, counts, history_valid);
  constants.jitter = glm::vec4(jitter_, previous_jitter_);
  scene_->set_frame_constants(constants);
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
  // A spread from no lit point (no lights at load) says nothing: the count rules decide then.
  if (const LightSpread& spread = scene_->data().light_spread; spread.points > 0) {
    inputs_.light_spread = spread.spread;
  }
  inputs_.max_gloss = scene_->data().max_gloss;
  inputs_.denoised = frame_output_ == FrameOutput::Denoised && denoise_.enabled;
  hdr = integrator_->add_passes(graph, inputs_, hdr);
  if (volume_camera_) {
    hdr = volume_camera_->add_pass(graph, inputs_, hdr, integrator_->volume_sampling());
  }
  raw_ = hdr;
  if (frame_output_ == FrameOutput::Denoised) {
    hdr = denoiser_->add_passes(graph, inputs_, denoise_, hdr, integrator_->sample_confidence());
  }
  if (width_ != output_width_ || height_ != output_height_) {
    hdr = upscaler_->add_pass(graph, inputs_, hdr, output_width_, output_height_, jitter_);
  }
  ++frames_;
  resized_ = false;
  return hdr;
}

runtime::graph::ImageHandle FrameRenderer::add_output_pass(runtime::graph::RenderGraph& graph,
                                                           runtime::graph::BufferHandle hdr,
                                                           runtime::graph::ImageHandle target,
                                                           float exposure) {
  return add_frame_output_pass(graph, *output_, hdr, target, output_width_, output_height_,
                               exposure);
}

}  // namespace lantern::lighting
