// Denoiser: the denoise.* pass chain between the integrator's raw HDR image and what a player, a
// PNG or a video sees (SVGF/ReLAX-style, Schied et al. 2017), with its own history in the render
// graph:
//   denoise.temporal   raw radiance -> demodulated illumination ((radiance - emission) / albedo;
//                      the sky kept, and emitters where the level has media),
//                      reprojected history (motion vectors, ReSTIR's restir_surfaces_similar
//                      disocclusion test), anti-firefly clamp, blend; luminance moments
//   denoise.variance   spatial variance where the history is short (< 4 frames)
//   denoise.atrous xN-1  variance-guided edge-avoiding à-trous
//   denoise.atrous_modulate  the last à-trous step, back to radiance (emission + illumination x
//                      albedo; pass-through pixels raw) -> "denoise.output"
//   denoise.modulate   the same without à-trous steps (atrous 0: temporal accumulation only)
// History ("denoise.surface_keys", "denoise.color", "denoise.moments") is the graph's: the frame
// renderer's invalidate_history() on a cut, a resize or the first frame leaves none, and a frame
// rendered without the denoiser leaves none for the next.
#pragma once

#include <array>
#include <string>

#include "lighting/denoise/denoise_pass.h"
#include "lighting/denoise/denoise_settings.h"
#include "lighting/frame/frame_inputs.h"
#include "runtime/runtime_fwd.h"

namespace lantern::lighting {

class Denoiser {
 public:
  Denoiser(runtime::Device& device, runtime::ShaderLibrary& shaders);

  void warm_up();
  // Adds the chain; `raw` is width*height vec4 linear radiance; returns the denoised buffer (same
  // layout). `confidence` (Integrator::sample_confidence, optional) weighs each frame's pixel in
  // the temporal accumulation by its M. With settings.enabled false it adds nothing and returns
  // `raw`.
  [[nodiscard]] runtime::graph::BufferHandle add_passes(
      runtime::graph::RenderGraph& graph, const FrameInputs& inputs,
      const DenoiseSettings& settings, runtime::graph::BufferHandle raw,
      runtime::graph::BufferHandle confidence = {}) const;

  static gpu::DenoisePush make_push(const DenoiseSettings& s, const FrameInputs& inputs);

 private:
  runtime::Device& device_;
  DenoisePass temporal_;
  DenoisePass variance_;
  DenoisePass atrous_;
  DenoisePass atrous_modulate_;
  DenoisePass modulate_;
};

}  // namespace lantern::lighting
