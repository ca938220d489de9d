// Denoiser: settings -> push constants, history and scratch buffers -> the denoise.* passes in
// order (denoiser.h).
#include "lighting/denoise/denoiser.h"

#include "lighting/restir/restir_settings.h"
#include "lighting/scene/gpu_scene.h"
#include "shared/light_eval.h"
#include "shared/restir.h"

namespace lantern::lighting {

using runtime::graph::BufferHandle;

Denoiser::Denoiser(runtime::Device& device, runtime::ShaderLibrary& shaders)
    : device_(device),
      temporal_(device, shaders, "temporal"),
      variance_(device, shaders, "variance"),
      atrous_(device, shaders, "atrous", DenoisePass::Threads::PixelPairs),
      atrous_modulate_(device, shaders, "atrous_modulate", DenoisePass::Threads::PixelPairs),
      modulate_(device, shaders, "modulate") {}

void Denoiser::warm_up() {
  const std::array<const runtime::ComputePipeline*, 5> pipelines{
      &temporal_.pipeline(), &variance_.pipeline(), &atrous_.pipeline(),
      &atrous_modulate_.pipeline(), &modulate_.pipeline()};
  runtime::warm_up(device_, pipelines);
}

gpu::DenoisePush Denoiser::make_push(const DenoiseSettings& s, const FrameInputs& inputs) {
  gpu::DenoisePush p{};
  p.width = inputs.width;
  p.height = inputs.height;
  p.color_alpha = s.color_alpha;
  p.moments_alpha = s.moments_alpha;
  p.phi_luminance = s.phi_luminance;
  p.phi_normal = s.phi_normal;
  p.phi_depth = s.phi_depth;
  p.firefly = s.firefly;
  p.neighbour_clamp = s.neighbour_clamp;
  p.antilag = s.antilag;
  // Stabilisation needs the à-trous chain: its last step blends (denoise.atrous_modulate).
  p.stabilize = s.atrous_iterations > 0 ? s.stabilize : 0.0f;
  p.stabilize_band = s.stabilize_band;
  p.repay = s.repay;
  p.max_history = s.max_history;
  // Levels with volumes: the fog in front of the sky is as noisy as any lit surface, so sky
  // pixels are filtered as a surface where camera rays end (volume passes, light_eval.h).
  const bool media = inputs.scene != nullptr && inputs.scene->volume_count() > 0;
  p.sky_distance = media ? gpu::kDirectionalShadowRadii * inputs.scene->scene_radius() : 0.0f;
  // Emitters are filtered for the light they reflect (their radiance less the G-buffer emission)
  // except with media: there the camera's pass has scaled the emission by a sampled transmittance
  // and added in-scattered light, so the difference is not the reflected light.
  if (!media) p.flags |= gpu::kDenoiseFlagFilterEmitters;
  // Reprojection rejects history exactly where ReSTIR's temporal reuse does by default (the same
  // test, restir_surfaces_similar, with RestirSettings' default thresholds; roughness 0.25 as
  // RestirIntegrator::make_push).
  const RestirSettings restir;
  p.similarity = {restir.depth_threshold, restir.normal_threshold, 0.25f, 0.0f};
  return p;
}

BufferHandle Denoiser::add_passes(runtime::graph::RenderGraph& graph, const FrameInputs& inputs,
                                  const DenoiseSettings& s, BufferHandle raw,
                                  BufferHandle confidence) const {
  if (!s.enabled) return raw;
  gpu::DenoisePush push = make_push(s, inputs);
  const VkDeviceSize pixels = VkDeviceSize{inputs.width} * inputs.height;
  const runtime::graph::BufferDesc vec4s{pixels * 4 * sizeof(float)};

  BufferHandle surface_keys = graph.create_history_buffer(
      "denoise.surface_keys", {pixels * sizeof(gpu::RestirSimilarityKey)});
  BufferHandle color = graph.create_history_buffer("denoise.color", vec4s);
  BufferHandle moments = graph.create_history_buffer("denoise.moments", vec4s);
  const BufferHandle surface_keys_history = graph.history(surface_keys);
  const BufferHandle color_history = graph.history(color);
  const BufferHandle moments_history = graph.history(moments);
  const bool history =
      surface_keys_history.valid() && color_history.valid() && moments_history.valid();
  if (history) push.flags |= gpu::kDenoiseFlagHistoryValid;
  // denoise.stable: the stabilised output, kept from frame to frame only while stabilising;
  // denoise.temporal reprojects it into denoise.stable_reprojected, which the last à-trous step
  // blends. Off, neither shader touches them: one-element stand-ins are bound (a level that does
  // not stabilise pays nothing for them).
  const bool stabilize = push.stabilize > 0.0f;
  const runtime::graph::BufferDesc stable_desc =
      stabilize ? vec4s : runtime::graph::BufferDesc{4 * sizeof(float)};
  BufferHandle stable = stabilize ? graph.create_history_buffer("denoise.stable", stable_desc)
                                  : graph.create_buffer("denoise.stable", stable_desc);
  const BufferHandle stable_history = stabilize ? graph.history(stable) : BufferHandle{};
  if (history && stable_history.valid()) push.flags |= gpu::kDenoiseFlagStableHistory;
  BufferHandle stable_reprojected =
      graph.create_buffer("denoise.stable_reprojected", stable_desc);
  // denoise.owed: the light the clamps took and have not given back, kept only while repaying
  // (push.repay > 0); off, a one-element stand-in that neither side touches.
  const bool repay = push.repay > 0.0f;
  BufferHandle owed = repay ? graph.create_history_buffer("denoise.owed", vec4s)
                            : graph.create_buffer("denoise.owed", {4 * sizeof(float)});
  const BufferHandle owed_history = repay ? graph.history(owed) : BufferHandle{};
  if (history && owed_history.valid()) push.flags |= gpu::kDenoiseFlagOwedHistory;
  if (!s.confidence) confidence = {};
  if (confidence.valid()) push.flags |= gpu::kDenoiseFlagConfidence;

  // denoise.temporal: its result is next frame's colour history (the unfiltered accumulation:
  // feeding the à-trous output back, as SVGF does, kept light the filter had spread into dark
  // contact shadows for frames: cornell_lights' relMSE 0.8-9.7 -> see README).
  const bool filter = s.atrous_iterations > 0;
  BufferHandle accum = color;
  BufferHandle guide = graph.create_buffer("denoise.guide", vec4s);
  {
    const std::vector<BufferHandle> out = temporal_.add(
        graph, inputs, push,
        {{"hdr_in", raw},
         {"surface_keys_out", surface_keys, DenoisePass::Buffer::Write},
         // Without history the shader does not read these: this frame's raw stands in.
         {"surface_keys_history", history ? surface_keys_history : raw},
         {"color_history", history ? color_history : raw},
         {"moments_history", history ? moments_history : raw},
         // Without a confidence buffer the shader does not read it: raw stands in.
         {"confidence_in", confidence.valid() ? confidence : raw},
         {"accum_out", accum, DenoisePass::Buffer::Write},
         {"moments_out", moments, DenoisePass::Buffer::Write},
         {"guide_out", guide, DenoisePass::Buffer::Write},
         // Read only with kDenoiseFlagStableHistory; written only while stabilising.
         {"stable_history", push.flags & gpu::kDenoiseFlagStableHistory ? stable_history : raw},
         {"stable_reprojected_out", stable_reprojected, DenoisePass::Buffer::Write},
         // Read only with kDenoiseFlagOwedHistory; written only while repaying.
         {"owed_history", push.flags & gpu::kDenoiseFlagOwedHistory ? owed_history : raw},
         {"owed_out", owed, DenoisePass::Buffer::Write}});
    accum = out[1];
    moments = out[2];
    guide = out[3];
    stable_reprojected = out[4];
  }

  const BufferHandle output = graph.create_buffer("denoise.output", vec4s);
  if (!filter) {
    // denoise.modulate: the temporal accumulation back to radiance.
    return modulate_.add(graph, inputs, push,
                         {{"accum_in", accum},
                          {"hdr_in", raw},
                          {"hdr_out", output, DenoisePass::Buffer::Write}})[0];
  }
  // denoise.variance, then the à-trous iterations ping-ponging two scratch buffers; the last one
  // (denoise.atrous_modulate) writes radiance.
  const std::vector<BufferHandle> filtered = variance_.add(
      graph, inputs, push,
      {{"accum_in", accum},
       {"guide", guide},
       {"moments_in", moments},
       {"accum_out", graph.create_buffer("denoise.variance", vec4s), DenoisePass::Buffer::Write},
       {"luminance_out", graph.create_buffer("denoise.luminance", {pixels * sizeof(float)}),
        DenoisePass::Buffer::Write}});
  BufferHandle current = filtered[0];
  const BufferHandle smooth_luminance = filtered[1];
  BufferHandle scratch[2];
  auto step_push = [&](std::uint32_t i) {
    gpu::DenoisePush p = push;
    p.step = 1u << i;
    if (i == 0) p.flags |= gpu::kDenoiseFlagSmoothLuminance;
    return p;
  };
  const std::uint32_t last = s.atrous_iterations - 1;
  for (std::uint32_t i = 0; i < last; ++i) {
    BufferHandle& target = scratch[i % 2];
    if (!target) target = graph.create_buffer(i % 2 ? "denoise.atrous.a" : "denoise.atrous.b", vec4s);
    target = atrous_.add(graph, inputs, step_push(i),
                         {{"accum_in", current},
                          {"guide", guide},
                          {"luminance_in", smooth_luminance},
                          {"accum_out", target, DenoisePass::Buffer::Write}})[0];
    current = target;
  }
  return atrous_modulate_.add(graph, inputs, step_push(last),
                              {{"accum_in", current},
                               {"guide", guide},
                               {"luminance_in", smooth_luminance},
                               {"hdr_in", raw},
                               {"hdr_out", output, DenoisePass::Buffer::Write},
                               {"stable_in", stable_reprojected},
                               {"stable_out", stable, DenoisePass::Buffer::Write}})[0];
}

}  // namespace lantern::lighting
