// DenoisePass: a denoise.* ShaderPass with one thread per pixel or pixel pair (denoise_pass.h).
#include "lighting/denoise/denoise_pass.h"

#include "lighting/frame/tile_order.h"

namespace lantern::lighting {

DenoisePass::DenoisePass(runtime::Device& device, runtime::ShaderLibrary& shaders,
                         const std::string& stage, Threads threads)
    : pass_(device, shaders, "denoise." + stage, "denoise/denoise_" + stage + ".comp", {},
            pixel_group_constants(device)),
      threads_(threads) {}

std::vector<runtime::graph::BufferHandle> DenoisePass::add(
    runtime::graph::RenderGraph& graph, const FrameInputs& inputs, const gpu::DenoisePush& push,
    std::initializer_list<Buffer> buffers) const {
  const std::uint32_t columns = threads_ == Threads::PixelPairs
                                    ? gpu::denoise_atrous_pair_columns(push.width, push.step)
                                    : push.width;
  return pass_.add(graph, inputs, push, buffers, {.x = columns, .y = push.height, .threads = true});
}

}  // namespace lantern::lighting
