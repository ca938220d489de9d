// integrators.baseline: reads the G-buffer and the scene, writes the HDR buffer; one workgroup
// per shuffled 8x8 tile (shaders/integrators/baseline.comp).
#include "lighting/integrators/baseline_integrator.h"

#include <numeric>

#include "integrators/baseline.h"
#include "lighting/scene/gpu_scene.h"
#include "runtime/gpu/bindings.h"

namespace lantern::lighting {
namespace {

using runtime::graph::Access;
using runtime::graph::BufferHandle;
using runtime::graph::ImageHandle;

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

BufferHandle BaselineIntegrator::add_passes(runtime::graph::RenderGraph& graph,
                                            const FrameInputs& inputs, BufferHandle hdr) {
  struct Data {
    BufferHandle hdr;
    ImageHandle position, normal, emission, ids;
  };
  const std::uint32_t width = inputs.width;
  const std::uint32_t height = inputs.height;
  gpu::BaselinePush push{};
  push.frame_index = inputs.frame_index;
  push.light_count = inputs.light_count;
  push.scene_radius = inputs.scene->scene_radius();
  const std::uint32_t tiles = ((width + gpu::kBaselineTileSize - 1) / gpu::kBaselineTileSize) *
                              ((height + gpu::kBaselineTileSize - 1) / gpu::kBaselineTileSize);
  push.tile_stride = tile_stride(tiles);
  const GpuScene* scene = inputs.scene;
  const Data& data = graph.add_pass<Data>(
      "integrators.baseline", runtime::graph::PassKind::Compute,
      [&](runtime::graph::PassBuilder& b, Data& d) {
        inputs.scene_handles.declare_reads(b);
        d.position = inputs.gbuffer.position;
        d.normal = inputs.gbuffer.normal;
        d.emission = inputs.gbuffer.emission_metallic;
        d.ids = inputs.gbuffer.ids;
        for (ImageHandle h : {d.position, d.normal, d.emission, d.ids}) {
          b.read(h, Access::StorageRead);
        }
        d.hdr = b.write(hdr, Access::StorageWrite);
      },
      [this, scene, push, tiles](runtime::graph::PassContext& ctx, const Data& d) {
        runtime::Bindings bindings(pipeline_);
        scene->bind(bindings);
        bindings.buffer("radiance", ctx.buffer(d.hdr), 0, VK_WHOLE_SIZE)
            .image_view("gbuffer_position", ctx.view(d.position), VK_IMAGE_LAYOUT_GENERAL)
            .image_view("gbuffer_normal", ctx.view(d.normal), VK_IMAGE_LAYOUT_GENERAL)
            .image_view("gbuffer_emission_metallic", ctx.view(d.emission), VK_IMAGE_LAYOUT_GENERAL)
            .image_view("gbuffer_ids", ctx.view(d.ids), VK_IMAGE_LAYOUT_GENERAL);
        pipeline_.bind(ctx.cmd(), bindings);
        pipeline_.push_constants(ctx.cmd(), push);
        pipeline_.dispatch(ctx.cmd(), tiles);
      });
  return data.hdr;
}

}  // namespace lantern::lighting
