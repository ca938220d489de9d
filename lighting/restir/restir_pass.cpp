// RestirPass: a restir.* ShaderPass with its dispatch over the image's tiles (restir_pass.h).
#include "lighting/restir/restir_pass.h"

#include "lighting/frame/tile_order.h"

namespace lantern::lighting {

RestirPass::RestirPass(runtime::Device& device, runtime::ShaderLibrary& shaders,
                       const std::string& stage, VisibilityBackend visibility)
    : pass_(device, shaders, "restir." + stage, "restir/restir_" + stage + ".comp",
            visibility_variant(visibility)) {}

RestirPass::RestirPass(runtime::Device& device, runtime::ShaderLibrary& shaders,
                       const std::string& name, const std::string& stage,
                       std::string_view variant)
    : pass_(device, shaders, name, "restir/restir_" + stage + ".comp", variant) {}

std::vector<runtime::graph::BufferHandle> RestirPass::add(runtime::graph::RenderGraph& graph,
                                                          const FrameInputs& inputs,
                                                          const gpu::RestirPush& push,
                                                          std::initializer_list<Buffer> buffers,
                                                          std::uint32_t workgroups) const {
  const std::uint32_t groups =
      workgroups != 0 ? workgroups : tile_count(inputs.width, inputs.height, gpu::kRestirTileSize);
  return pass_.add(graph, inputs, push, buffers, {.x = groups});
}

}  // namespace lantern::lighting
