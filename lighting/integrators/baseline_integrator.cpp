// integrators.baseline: reads the G-buffer and the scene, writes the HDR buffer; one workgroup
// per shuffled 8x8 tile (shaders/integrators/baseline.comp).
#include "lighting/integrators/baseline_integrator.h"

#include <fmt/format.h>

#include "engine/core/error.h"
#include "integrators/baseline.h"
#include "lighting/frame/tile_order.h"
#include "lighting/integrators/gbuffer_shading_pass.h"
#include "lighting/scene/gpu_scene.h"

namespace lantern::lighting {

using runtime::graph::BufferHandle;

BaselineIntegrator::BaselineIntegrator(runtime::Device& device, runtime::ShaderLibrary& shaders)
    : pipeline_(device, shaders.load("integrators/baseline.comp"),
                runtime::ComputePipelineDesc{.name = "integrators.baseline", .constants = {}}) {}

void BaselineIntegrator::check_settings(
    const std::vector<std::pair<std::string, std::string>>& settings) {
  if (settings.empty()) return;
  throw InputError(fmt::format(
      "--set {}: the baseline integrator has no settings (1 sample per pixel per frame)",
      settings.front().first));
}

BufferHandle BaselineIntegrator::add_passes(runtime::graph::RenderGraph& graph,
                                            const FrameInputs& inputs, BufferHandle hdr) {
  const std::uint32_t width = inputs.width;
  const std::uint32_t height = inputs.height;
  gpu::BaselinePush push{};
  const std::uint32_t tiles = tile_count(width, height, gpu::kBaselineTileSize);
  push.tile_stride = tile_stride(tiles);
  return add_gbuffer_shading_pass(graph, "integrators.baseline", pipeline_, inputs, push, tiles,
                                  hdr);
}

}  // namespace lantern::lighting
