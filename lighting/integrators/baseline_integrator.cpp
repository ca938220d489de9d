// integrators.baseline: binds the scene and dispatches one thread per pixel.
#include "lighting/integrators/baseline_integrator.h"

#include "integrators/baseline.h"
#include "runtime/gpu/bindings.h"

namespace lantern::lighting {

BaselineIntegrator::BaselineIntegrator(runtime::Device& device, runtime::ShaderLibrary& shaders)
    : pipeline_(device, shaders.load("integrators/baseline.comp"),
                runtime::ComputePipelineDesc{.name = "integrators.baseline", .constants = {}}) {}

void BaselineIntegrator::record(VkCommandBuffer cmd, const GpuScene& scene,
                                const runtime::Buffer& frame_constants,
                                const runtime::Buffer& radiance, std::uint32_t width,
                                std::uint32_t height, std::uint32_t frame_index) const {
  runtime::Bindings bindings(pipeline_);
  scene.bind(bindings);
  bindings.buffer("frame_constants", frame_constants).buffer("radiance", radiance);
  pipeline_.bind(cmd, bindings);
  gpu::BaselinePush push{};
  push.frame_index = frame_index;
  push.light_count = scene.light_count();
  push.scene_radius = scene.scene_radius();
  pipeline_.push_constants(cmd, push);
  pipeline_.dispatch_threads(cmd, width, height);
}

}  // namespace lantern::lighting
