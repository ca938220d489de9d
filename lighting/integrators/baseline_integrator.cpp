// integrators.baseline: reads the G-buffer and the scene, writes the HDR buffer; one workgroup
// per shuffled tile of the device's pixel group shape (shaders/integrators/baseline.comp).
#include "lighting/integrators/baseline_integrator.h"

#include <fmt/format.h>

#include "engine/core/error.h"
#include "integrators/baseline.h"
#include "lighting/frame/tile_order.h"
#include "lighting/integrators/gbuffer_shading_pass.h"
#include "lighting/scene/gpu_scene.h"
#include "lighting/visibility/host_visibility.h"

namespace lantern::lighting {

using runtime::graph::BufferHandle;

BaselineIntegrator::BaselineIntegrator(runtime::Device& device, runtime::ShaderLibrary& shaders,
                                       VisibilityBackend visibility)
    : device_(device),
      shaders_(shaders),
      visibility_(visibility),
      pipeline_(device, shaders.load("integrators/baseline.comp", visibility_variant(visibility)),
                runtime::ComputePipelineDesc{
                    .name = "integrators.baseline",
                    .constants = pixel_group_constants(device)}) {}

void BaselineIntegrator::warm_up() {
  // With host visibility the BVH's pass never runs: its two variants are JIT-compiled instead.
  if (!host_) {
    pipeline_.warm_up();
    return;
  }
  emit_->pipeline().warm_up();
  occluded_->pipeline().warm_up();
}

void BaselineIntegrator::prepare(const GpuScene& scene) {
  host_ = scene.host_visibility();
  if (host_ != nullptr && !emit_) {
    // The same workgroup shape as pipeline_, whose tiles they are dispatched over.
    emit_ = std::make_unique<ShaderPass>(device_, shaders_, "integrators.baseline",
                                         "integrators/baseline.comp", "hostemit",
                                         pixel_group_constants(device_));
    occluded_ = std::make_unique<ShaderPass>(device_, shaders_, "integrators.baseline_occluded",
                                             "integrators/baseline.comp", "hostresolve",
                                             pixel_group_constants(device_));
  }
}

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
  const std::uint32_t tiles = tile_count(width, height, pipeline_);
  push.tile_stride = tile_stride(tiles);
  if (host_ == nullptr) {
    return add_gbuffer_shading_pass(graph, "integrators.baseline", pipeline_, inputs, push, tiles,
                                    hdr);
  }
  // Host visibility: the shading as if every ray got through (and the rays), visibility.host,
  // then the blocked pixels rewritten.
  const BufferHandle rays =
      host_->add_shadow_rays(graph, width * height, [&](BufferHandle empty) {
        const std::vector<BufferHandle> shaded =
            emit_->add(graph, inputs, push,
                       {{"host_rays", empty, ShaderPassBuffer::Write},
                        {"radiance", hdr, ShaderPassBuffer::Write}},
                       {.x = tiles});
        hdr = shaded[1];
        return shaded[0];
      });
  return occluded_->add(graph, inputs, push,
                        {{"host_rays", rays}, {"radiance", hdr, ShaderPassBuffer::ReadWrite}},
                        {.x = tiles})[0];
}

}  // namespace lantern::lighting
