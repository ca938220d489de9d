// FrameRenderer: one frame of a level from its FrameSnapshot, as render-graph passes:
//   scene.upload (GpuScene: instances with previous transforms, TLAS, lights + remap, constants)
//   -> gbuffer (lighting/gbuffer/gbuffer_pass.h) -> the integrator's passes (the raw image)
//   -> [denoise.* (lighting/denoise/denoiser.h)] -> [upscale.temporal to the output size]
//   -> the HDR buffer.
// It owns the GpuScene, the G-buffer pass and the Integrator; the FrameSession
// (lighting/frame/frame_session.h) owns the graph, the executor and the target and drives it:
//
//   FrameRenderer renderer(device, shaders, level, make_integrator(device, shaders, config), w, h,
//   1); renderer.warm_up(); FrameSession session(device, target, renderer);
//   session.render(world.step());
#pragma once

#include <cstdint>
#include <memory>
#include <string_view>

#include "engine/world/frame_snapshot.h"
#include "lighting/denoise/denoise_settings.h"
#include "lighting/frame/frame_inputs.h"
#include "lighting/gbuffer/gbuffer_method.h"
#include "lighting/scene/gpu_scene.h"
#include "runtime/graph/render_graph.h"
#include "runtime/runtime_fwd.h"

namespace lantern::lighting {

class GBufferPass;
class Denoiser;
class Upscaler;
class VolumeCameraPass;

// Which image add_frame returns (what the output pass shows): the integrator's raw radiance
// (unbiased: bias tests, trade's raw error, EXR by default) or the denoised one (what a player,
// a PNG or a video sees; lighting/denoise/denoiser.h).
enum class FrameOutput : std::uint8_t { Raw, Denoised };
// "raw" | "denoised"; InputError naming the value otherwise.
FrameOutput parse_frame_output(std::string_view text);
const char* frame_output_name(FrameOutput output);

class FrameRenderer {
 public:
  // Builds and uploads the scene of `level` (InputError on bad level data or size 0).
  FrameRenderer(runtime::Device& device, runtime::ShaderLibrary& shaders,
                std::shared_ptr<const Level> level, std::unique_ptr<Integrator> integrator,
                std::uint32_t width, std::uint32_t height, std::uint32_t seed);
  ~FrameRenderer();
  FrameRenderer(const FrameRenderer&) = delete;
  FrameRenderer& operator=(const FrameRenderer&) = delete;

  // JIT-compiles every pipeline (G-buffer, integrator, output) outside the timed frames.
  void warm_up();

  // Adds this frame's passes (scene.upload, gbuffer, the integrator's, and with
  // FrameOutput::Denoised the denoise.* chain) to `graph` (between its begin_frame() and bake())
  // and returns the HDR buffer of output(): output_width*output_height vec4 linear radiance
  // (upscale.temporal reconstructs it when the internal size is smaller).
  [[nodiscard]] runtime::graph::BufferHandle add_frame(runtime::graph::RenderGraph& graph,
                                                       const FrameSnapshot& snapshot);
  // frame.output: `hdr` -> `target` (rgba32f image of the output size). exposure 0: linear
  // copy (EXR, readback); > 0: exposure x filmic tonemap (display-referred linear, for a window).
  [[nodiscard]] runtime::graph::ImageHandle add_output_pass(runtime::graph::RenderGraph& graph,
                                                            runtime::graph::BufferHandle hdr,
                                                            runtime::graph::ImageHandle target,
                                                            float exposure);

  // What add_frame returns from the next frame on (default Raw: no denoise pass runs).
  void set_output(FrameOutput output) { frame_output_ = output; }
  FrameOutput output() const { return frame_output_; }
  // The denoiser's knobs from the next frame on (a change keeps its history).
  void set_denoise_settings(const DenoiseSettings& settings) { denoise_ = settings; }
  // --set gbuffer=METHOD (lighting/gbuffer/gbuffer_method.h): how later frames make the
  // G-buffer (InputError for host on a scene without host visibility, at the next frame).
  void set_gbuffer_method(GBufferMethod method);
  const DenoiseSettings& denoise_settings() const { return denoise_; }
  // The integrator's raw HDR buffer of the last add_frame (valid for that graph frame only): a
  // hook can read back the raw image while the output shows the denoised one.
  runtime::graph::BufferHandle last_raw() const { return raw_; }

  // Sub-pixel jitter of the G-buffer's samples (Halton 2,3 over 8 frames, FrameConstants.jitter):
  // what upscale.temporal reconstructs from. Default: on exactly while the internal size is
  // below the output size; force it on or off for tests. Motion vectors follow it (gbuffer.h).
  enum class Jitter : std::uint8_t { WhenUpscaling, On, Off };
  void set_jitter(Jitter jitter) { jitter_mode_ = jitter; }
  // This frame's sample offset from the pixel centres (pixels; 0 when off), after add_frame.
  glm::vec2 jitter() const { return jitter_; }
  // The offset of the samples of the renderer's frame `frame` (counted from its first, cuts
  // included) while the jitter is on: Halton (2, 3) points 1..8, centred on the pixel.
  static glm::vec2 jitter_sequence(std::uint32_t frame);

  // A new output size (the internal size follows it): the next frame has no history.
  void resize(std::uint32_t width, std::uint32_t height);
  // The internal (render) size the G-buffer, the integrator and the denoiser run at, clamped to
  // 1..output size; below the output size upscale.temporal (lighting/upscale/upscaler.h)
  // reconstructs the output. A change drops history like a resize.
  void set_internal_size(std::uint32_t width, std::uint32_t height);

  // Whether the last add_frame kept temporal history (false on the first frame, after a camera
  // cut or a resize: it invalidated the graph's history).
  bool history_valid() const { return history_valid_; }
  const GpuScene& scene() const { return *scene_; }
  GpuScene& scene() { return *scene_; }
  Integrator& integrator() { return *integrator_; }
  // What the last add_frame handed the integrator (handles valid for that graph frame only).
  const FrameInputs& last_inputs() const { return inputs_; }
  // The internal (render) size; the output size the target gets.
  std::uint32_t width() const { return width_; }
  std::uint32_t height() const { return height_; }
  std::uint32_t output_width() const { return output_width_; }
  std::uint32_t output_height() const { return output_height_; }
  std::uint32_t frames_rendered() const { return frames_; }

 private:
  std::unique_ptr<GpuScene> scene_;
  std::unique_ptr<GBufferPass> gbuffer_;
  std::unique_ptr<Integrator> integrator_;
  std::unique_ptr<Denoiser> denoiser_;
  std::unique_ptr<Upscaler> upscaler_;
  // Levels with volumes whose integrator does not render the media itself.
  std::unique_ptr<VolumeCameraPass> volume_camera_;
  DenoiseSettings denoise_;
  FrameOutput frame_output_ = FrameOutput::Raw;
  Jitter jitter_mode_ = Jitter::WhenUpscaling;
  glm::vec2 jitter_{0.0f};
  glm::vec2 previous_jitter_{0.0f};
  runtime::graph::BufferHandle raw_;
  std::unique_ptr<runtime::ComputePipeline> output_;
  std::uint32_t width_;
  std::uint32_t height_;
  std::uint32_t output_width_;
  std::uint32_t output_height_;
  std::uint32_t seed_;
  std::uint32_t frames_ = 0;
  bool resized_ = false;
  bool history_valid_ = false;
  FrameInputs inputs_;
};

}  // namespace lantern::lighting
