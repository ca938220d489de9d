// integrators.baseline: per pixel, the G-buffer's primary hit, its emission seen from the camera,
// and one light sample from the power alias table with one shadow ray
// (shaders/integrators/baseline.comp). The simple, unbiased estimator ReSTIR is compared with.
// Settings: none (1 sample per pixel per frame); any --set key is an InputError.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "lighting/frame/frame_inputs.h"
#include "lighting/frame/shader_pass.h"
#include "runtime/gpu/compute_pipeline.h"
#include "runtime/gpu/shader_library.h"

namespace lantern::lighting {

class HostVisibility;

class BaselineIntegrator final : public Integrator {
 public:
  static constexpr const char* kName = "baseline";

  BaselineIntegrator(runtime::Device& device, runtime::ShaderLibrary& shaders,
                     VisibilityBackend visibility = VisibilityBackend::Bvh);

  // It has none: InputError naming the first key of a non-empty `settings`.
  static void check_settings(const std::vector<std::pair<std::string, std::string>>& settings);

  const char* name() const override { return kName; }
  void warm_up() override;
  VisibilityBackend visibility() const override { return visibility_; }
  // Host visibility: the scene's HostVisibility answers the shadow rays (prepare).
  void prepare(const GpuScene& scene) override;
  // One shadow ray per pixel (as restir.shade), so bench reports baseline's shadow rays/s too
  // (traced by visibility.host with host visibility).
  std::vector<std::pair<std::string, double>> shadow_rays_per_pixel() const override {
    return {{host_ != nullptr ? "visibility.host" : "integrators.baseline", 1.0}};
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
  runtime::Device& device_;
  runtime::ShaderLibrary& shaders_;
  VisibilityBackend visibility_;
  runtime::ComputePipeline pipeline_;
  // Host visibility: integrators.baseline (its "hostemit" variant) shades as if every ray got
  // through and writes the rays, visibility.host traces them, integrators.baseline_occluded
  // rewrites the pixels whose ray was blocked.
  HostVisibility* host_ = nullptr;
  std::unique_ptr<ShaderPass> emit_;
  std::unique_ptr<ShaderPass> occluded_;
};

}  // namespace lantern::lighting
