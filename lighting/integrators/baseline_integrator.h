// integrators.baseline: per pixel, the G-buffer's primary hit, its emission seen from the camera,
// and one light sample from the power alias table with one shadow ray
// (shaders/integrators/baseline.comp). The simple, unbiased estimator ReSTIR is compared with.
// Settings: none (1 sample per pixel per frame); any --set key is an InputError.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "lighting/frame/frame_inputs.h"
#include "runtime/gpu/compute_pipeline.h"
#include "runtime/gpu/shader_library.h"

namespace lantern::lighting {

class BaselineIntegrator final : public Integrator {
 public:
  static constexpr const char* kName = "baseline";

  BaselineIntegrator(runtime::Device& device, runtime::ShaderLibrary& shaders);

  // It has none: InputError naming the first key of a non-empty `settings`.
  static void check_settings(const std::vector<std::pair<std::string, std::string>>& settings);

  const char* name() const override { return kName; }
  void warm_up() override { pipeline_.warm_up(); }
  // One shadow ray per pixel (as restir.shade), so bench reports baseline's shadow rays/s too.
  std::vector<std::pair<std::string, double>> shadow_rays_per_pixel() const override {
    return {{"integrators.baseline", 1.0}};
  }
  std::vector<std::pair<std::string, std::string>> describe_settings() const override {
    return {};
  }
  void apply_settings(const std::vector<std::pair<std::string, std::string>>& changes) override {
    check_settings(changes);
  }
  // Writes every pixel of `hdr` (StorageWrite).
  [[nodiscard]] runtime::graph::BufferHandle add_passes(runtime::graph::RenderGraph& graph,
                                                        const FrameInputs& inputs,
                                                        runtime::graph::BufferHandle hdr) override;

 private:
  runtime::ComputePipeline pipeline_;
};

}  // namespace lantern::lighting
