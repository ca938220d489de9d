// ReSTIR DI as a lighting Integrator: per frame, restir.initial -> restir.temporal ->
// restir.spatial x N -> restir.shade, with the reservoir buffers each pass reads and writes
// chosen by ReservoirBuffers (reservoir_buffers.h) and mapped to render-graph resources here:
// "restir.reservoirs" (history: this frame's final reservoirs), "restir.surfaces" (history: the
// packed per-pixel surfaces, for next frame's disocclusion test), "restir.reservoirs.a/.b"
// (transient scratch), "restir.temporal_status" (transient, for the disocclusion view). Levels
// with volumes add the media reservoirs' passes after restir.shade (lighting/volume/
// volume_restir.h), which replace volume.camera for this integrator.
#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "lighting/frame/frame_inputs.h"
#include "lighting/restir/reservoir_buffers.h"
#include "lighting/restir/restir_pass.h"
#include "lighting/restir/restir_settings.h"
#include "lighting/volume/volume_restir.h"

namespace lantern::lighting {

class HostVisibility;

class RestirIntegrator final : public Integrator {
 public:
  static constexpr const char* kName = "restir";

  RestirIntegrator(runtime::Device& device, runtime::ShaderLibrary& shaders,
                   const RestirSettings& settings,
                   VisibilityBackend visibility = VisibilityBackend::Bvh);

  const char* name() const override { return kName; }
  void warm_up() override;
  // restir.shade traces one shadow ray per pixel (visibility.host does with host visibility);
  // restir.initial one more with initial_visibility.
  std::vector<std::pair<std::string, double>> shadow_rays_per_pixel() const override;
  VisibilityBackend visibility() const override { return visibility_; }
  // Creates the media reservoirs' passes when the scene has volumes.
  void prepare(const GpuScene& scene) override;
  bool renders_media() const override { return volume_ != nullptr; }
  // The final reservoirs of the frame add_passes built (their M).
  runtime::graph::BufferHandle sample_confidence() const override { return confidence_; }
  [[nodiscard]] runtime::graph::BufferHandle add_passes(runtime::graph::RenderGraph& graph,
                                                        const FrameInputs& inputs,
                                                        runtime::graph::BufferHandle hdr) override;

  const RestirSettings& settings() const { return settings_; }
  std::vector<std::pair<std::string, std::string>> describe_settings() const override {
    return describe(settings_);
  }
  // Checked by apply_setting (restir_settings.h); takes effect next frame, and a change of the
  // chain's shape keeps history (Final is always kept).
  void apply_settings(const std::vector<std::pair<std::string, std::string>>& changes) override;

  // The push constants a frame with these settings gets (the pass index and history flag aside;
  // each RestirPass sets the tile order of its own tiles).
  static gpu::RestirPush make_push(const RestirSettings& settings, const FrameInputs& inputs);
  // The light spread the rules below follow: the setting's, else the one measured at load, else
  // (not measured) the largest float.
  static float light_spread(const RestirSettings& settings, const FrameInputs& inputs);
  // Presampling tiles this frame gets: 0 when the lights fit in one tile, else the setting,
  // lowered so that the presampled entries stay at most 1/8 of the light candidates drawn, and
  // to the light spread rounded up (at least 1).
  static std::uint32_t presample_tiles(const RestirSettings& settings, const FrameInputs& inputs);
  // Below this light spread the local lists are off. The levels measured lie a factor of 2 or
  // more on either side: light_panels 4.1 (panels alike from everywhere, where the lists did not
  // pay), million_lights 33, harbour_fog 38, night_market 60 (lamps and lanterns that each light
  // their surroundings).
  static constexpr float kLocalListsMinSpread = 16.0f;
  // Whether the level's lights are many (at least local_min_lights) and each lights only its
  // surroundings (a light spread of at least kLocalListsMinSpread): where the local lists and the
  // light grid candidates are drawn.
  static bool lights_local(const RestirSettings& settings, const FrameInputs& inputs);
  // Draws per slot of restir.initial's local light lists this frame: the setting where the level
  // has at least local_min_lights lights and a light spread of at least kLocalListsMinSpread,
  // else 0.
  static std::uint32_t local_candidates(const RestirSettings& settings, const FrameInputs& inputs);
  // The light grid candidates drawn this frame: RestirSettings::grid_candidates where the local
  // lists are on (the same rule: many lights, each lighting its surroundings), else 0.
  static std::uint32_t grid_candidates(const RestirSettings& settings, const FrameInputs& inputs);
  // BSDF candidates a pixel at least bsdf_min_gloss glossy draws this frame: the setting, or 0
  // where no material of the level reaches bsdf_min_gloss (FrameInputs::max_gloss), so that a
  // level without such surfaces runs neither restir.initial_rays nor visibility.host_closest.
  static std::uint32_t bsdf_candidates(const RestirSettings& settings, const FrameInputs& inputs);

 private:
  // Whether the host traces restir.initial's BSDF candidates (host visibility and at least one
  // candidate): the one rule warm_up and add_passes follow. Makes the two passes
  // (initial_rays_, initial_closest_) the first time it is true.
  bool host_traces_bsdf(std::uint32_t bsdf_candidates);

  // This frame's final reservoirs, one per pixel (add_passes); none with reservoir_stride > 1,
  // whose reservoirs are per cell (the denoiser then counts every frame alike).
  runtime::graph::BufferHandle confidence_;
  runtime::Device& device_;
  runtime::ShaderLibrary& shaders_;
  RestirSettings settings_;
  VisibilityBackend visibility_;
  // restir.temporal's and restir.spatial's workgroup order on CPU devices (tile_order.h): bands
  // of tile rows keep the neighbours they read in the thread's cache (0.72-0.84x their time at
  // 640x360). restir.initial keeps the shuffle, which its presampled tiles rely on.
  std::uint32_t tile_bands_;
  RestirPass presample_;
  RestirPass initial_;
  RestirPass temporal_;
  RestirPass spatial_;
  RestirPass shade_;
  // Host visibility (a scene with HostVisibility, prepare): restir.shade (its "hostemit"
  // variant) writes the rays, visibility.host traces them, restir.shade_occluded rewrites the
  // pixels whose ray was blocked.
  HostVisibility* host_ = nullptr;
  std::unique_ptr<RestirPass> shade_emit_;
  std::unique_ptr<RestirPass> shade_occluded_;
  // With BSDF candidates: restir.initial_rays ("closestemit") writes their rays,
  // visibility.host_closest traces them, restir.initial ("closestresolve") reads the hits.
  std::unique_ptr<RestirPass> initial_rays_;
  std::unique_ptr<RestirPass> initial_closest_;
  ReservoirBuffers buffers_;
  std::unique_ptr<VolumeRestir> volume_;  // levels with volumes only (prepare)
};

}  // namespace lantern::lighting
