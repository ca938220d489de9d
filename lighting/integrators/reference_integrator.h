// integrators.reference: converged direct lighting (shaders/integrators/reference.comp). Per pixel
// the G-buffer's primary hit and `spp` samples per frame, each one light sample (environment or
// power alias table) and one BSDF sample (GGX VNDF / cosine), combined with the power heuristic;
// emissive triangles and the environment are reached by both strategies, punctual lights by light
// sampling only. Frames average to the converged image (offline_render's `average`); converged
// references are cached by lighting/integrators/reference_cache.h.
//
// The environment map is the scene's (GpuScene loads and uploads it once per level and binds it
// with the other scene buffers; a black 1-texel stand-in without one). Light selection: the
// environment with probability env_power / (env_power + emitters' total power), kept current in
// the env header by GpuScene, else the alias table (environment_map.h explains the power proxy).
//
// Settings (--set): spp=N, or reference.spp=N (samples per pixel per frame; IntegratorConfig.spp
// wins when non-zero). Any other key is an InputError.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "lighting/frame/frame_inputs.h"
#include "runtime/gpu/compute_pipeline.h"
#include "runtime/gpu/shader_library.h"

namespace lantern::lighting {

struct ReferenceSettings {
  std::uint32_t spp = 64;  // samples per pixel per frame (gpu::kReferenceDefaultSpp)
};

// Sets one key ("spp", alias "reference.spp") of `settings`; InputError on unknown keys and bad
// values.
void apply_reference_setting(ReferenceSettings& settings, std::string_view key,
                             std::string_view value);

// From --set pairs and --spp (0 = the default or the spp setting); InputError on unknown keys and
// bad values.
ReferenceSettings parse_reference_settings(
    const std::vector<std::pair<std::string, std::string>>& settings, std::uint32_t spp);

class ReferenceIntegrator final : public Integrator {
 public:
  ReferenceIntegrator(runtime::Device& device, runtime::ShaderLibrary& shaders,
                      const ReferenceSettings& settings,
                      VisibilityBackend visibility = VisibilityBackend::Bvh);
  ~ReferenceIntegrator() override;

  static constexpr const char* kName = "reference";

  const char* name() const override { return kName; }
  void warm_up() override { pipeline_.warm_up(); }
  std::vector<std::pair<std::string, std::string>> describe_settings() const override;
  void apply_settings(const std::vector<std::pair<std::string, std::string>>& changes) override;
  VisibilityBackend visibility() const override { return visibility_; }
  VolumeCameraSampling volume_sampling() const override {
    return {.samples = settings_.spp, .phase_mis = true};
  }
  // Writes every pixel of `hdr` (StorageWrite): the mean of this frame's spp samples.
  [[nodiscard]] runtime::graph::BufferHandle add_passes(runtime::graph::RenderGraph& graph,
                                                        const FrameInputs& inputs,
                                                        runtime::graph::BufferHandle hdr) override;

  const ReferenceSettings& settings() const { return settings_; }

 private:
  VisibilityBackend visibility_;
  runtime::ComputePipeline pipeline_;
  ReferenceSettings settings_;
};

}  // namespace lantern::lighting
