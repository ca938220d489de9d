// integrators.baseline: binds the scene and dispatches one workgroup per shuffled 8x8 tile.
#include "lighting/integrators/baseline_integrator.h"

#include <numeric>

#include "integrators/baseline.h"
#include "runtime/gpu/bindings.h"

namespace lantern::lighting {
namespace {

// A stride near count / golden ratio that is coprime to `count`, so g -> g * stride mod count
// is a permutation that scatters neighbouring workgroups across the image. 1 when the product
// could overflow 32 bits.
std::uint32_t tile_stride(std::uint32_t count) {
  if (count < 3 || count > 65535) return 1;
  std::uint32_t stride = static_cast<std::uint32_t>(static_cast<double>(count) * 0.6180339887);
  while (std::gcd(stride, count) != 1) ++stride;
  return stride;
}

}  // namespace

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
  const std::uint32_t tiles = ((width + gpu::kBaselineTileSize - 1) / gpu::kBaselineTileSize) *
                              ((height + gpu::kBaselineTileSize - 1) / gpu::kBaselineTileSize);
  push.tile_stride = tile_stride(tiles);
  pipeline_.push_constants(cmd, push);
  pipeline_.dispatch(cmd, tiles);
}

}  // namespace lantern::lighting
