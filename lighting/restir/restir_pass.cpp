// RestirPass: a restir.* ShaderPass with its dispatch over the image's tiles (restir_pass.h).
#include "lighting/restir/restir_pass.h"

#include "lighting/frame/tile_order.h"
#include "shared/pixel_groups.h"

namespace lantern::lighting {
namespace {
// The workgroup tile of restir_<stage>.comp on `device`: the device's pixel group shape
// (tile_order.h; rows on CPU devices), except restir.initial's: its workgroup's local light list
// is drawn towards the tile's own surface points, and a row of 64 pixels drew lists that served
// its pixels worse (night_market 160x90, seeds 1-3: the denoised mean 0.908-0.914 of the
// reference against 0.938-0.970, raw relMSE 11.0 / 2.65 / 4.83 against 2.04 / 3.40 / 2.28), so
// it keeps 8x8 squares on every device.
runtime::SpecConstants stage_constants(const runtime::Device& device, const std::string& stage) {
  if (stage == "initial") return pixel_group_constants(glm::uvec2(gpu::kPixelGroupGpuSide));
  return pixel_group_constants(device);
}
}  // namespace

RestirPass::RestirPass(runtime::Device& device, runtime::ShaderLibrary& shaders,
                       const std::string& stage, VisibilityBackend visibility)
    : pass_(device, shaders, "restir." + stage, "restir/restir_" + stage + ".comp",
            visibility_variant(visibility), stage_constants(device, stage)),
      over_cells_(stage != "shade") {}

RestirPass::RestirPass(runtime::Device& device, runtime::ShaderLibrary& shaders,
                       const std::string& name, const std::string& stage,
                       std::string_view variant)
    : pass_(device, shaders, name, "restir/restir_" + stage + ".comp", variant,
            stage_constants(device, stage)),
      over_cells_(stage != "shade") {}

std::vector<runtime::graph::BufferHandle> RestirPass::add(runtime::graph::RenderGraph& graph,
                                                          const FrameInputs& inputs,
                                                          const gpu::RestirPush& push,
                                                          std::initializer_list<Buffer> buffers,
                                                          std::uint32_t workgroups) const {
  if (workgroups != 0) return pass_.add(graph, inputs, push, buffers, {.x = workgroups});
  // The shuffle's stride for this pass's own tiles (its shape is the stage's), over the reservoir
  // grid's cells or the image's pixels.
  const glm::uvec2 extent = gpu::restir_grid_extent({inputs.width, inputs.height},
                                                    over_cells_ ? push.reservoir_stride : 1u);
  const std::uint32_t tiles = tile_count(extent.x, extent.y, pass_.pipeline());
  gpu::RestirPush p = push;
  p.tile_stride = tile_stride(tiles);
  return pass_.add(graph, inputs, p, buffers, {.x = tiles});
}

}  // namespace lantern::lighting
