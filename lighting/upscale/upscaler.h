// Upscaler: upscale.temporal, the pass between the internal-size image (denoised or raw) and the
// output size (shaders/upscale/upscale_temporal.comp): bilinear resampling of this frame's
// samples plus last frame's output reprojected along the scene's own motion (gbuffer.motion's
// zw, without the jitter step: the output is not jittered), fetched by Catmull-Rom and rectified
// against the current 3x3 neighbourhood. Its history ("upscale.color", output size) is the graph's:
// a cut, a resize or a change of internal size leaves none. The frame renderer adds it when the
// internal size differs from the output size (lighting/frame/frame_renderer.h).
#pragma once

#include <cstdint>

#include "lighting/frame/frame_inputs.h"
#include "runtime/gpu/compute_pipeline.h"
#include "runtime/runtime_fwd.h"
#include "shared/upscale.h"

namespace lantern::lighting {

class Upscaler {
 public:
  Upscaler(runtime::Device& device, runtime::ShaderLibrary& shaders);
  void warm_up() const { pipeline_.warm_up(); }

  // Share of the rectified history each output pixel keeps when the internal size is below the
  // output size (or samples are jittered): the reconstruction's steadiness against its lag.
  static constexpr float kHistoryWeight = 0.85f;
  // The push constants for `inputs` (the internal size) upscaled to out_width x out_height: no
  // history weight at scale 1 without jitter (nothing to reconstruct).
  static gpu::UpscalePush make_push(const FrameInputs& inputs, std::uint32_t out_width,
                                    std::uint32_t out_height, glm::vec2 jitter);

  // Adds upscale.temporal: `hdr` (inputs' size, its samples `jitter` pixels off the pixel
  // centres: the frame's FrameConstants.jitter.xy) -> a new out_width x out_height HDR buffer.
  [[nodiscard]] runtime::graph::BufferHandle add_pass(runtime::graph::RenderGraph& graph,
                                                      const FrameInputs& inputs,
                                                      runtime::graph::BufferHandle hdr,
                                                      std::uint32_t out_width,
                                                      std::uint32_t out_height,
                                                      glm::vec2 jitter = glm::vec2(0.0f)) const;

 private:
  runtime::ComputePipeline pipeline_;
};

}  // namespace lantern::lighting
