// integrators.baseline: per pixel, one camera ray, directly seen emission and one light sample
// from the power alias table with one shadow ray (shaders/integrators/baseline.comp). The
// simple, unbiased estimator ReSTIR is compared with.
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>

#include "lighting/scene/gpu_scene.h"
#include "runtime/gpu/compute_pipeline.h"
#include "runtime/gpu/shader_library.h"

namespace lantern::lighting {

class BaselineIntegrator {
 public:
  BaselineIntegrator(runtime::Device& device, runtime::ShaderLibrary& shaders);

  // JIT-compiles the shader now (lavapipe compiles at first dispatch), not in a timed frame.
  void warm_up() const { pipeline_.warm_up(); }

  // Records one frame: writes width * height vec4 radiance values (row-major, top-left first)
  // into `radiance`. `frame_constants` holds one gpu::FrameConstants.
  void record(VkCommandBuffer cmd, const GpuScene& scene, const runtime::Buffer& frame_constants,
              const runtime::Buffer& radiance, std::uint32_t width, std::uint32_t height,
              std::uint32_t frame_index) const;

 private:
  runtime::ComputePipeline pipeline_;
};

}  // namespace lantern::lighting
