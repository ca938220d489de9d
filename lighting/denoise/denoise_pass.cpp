// DenoisePass: a denoise.* ShaderPass with one thread per pixel (denoise_pass.h).
#include "lighting/denoise/denoise_pass.h"

namespace lantern::lighting {

DenoisePass::DenoisePass(runtime::Device& device, runtime::ShaderLibrary& shaders,
                         const std::string& stage)
    : pass_(device, shaders, "denoise." + stage, "denoise/denoise_" + stage + ".comp") {}

std::vector<runtime::graph::BufferHandle> DenoisePass::add(
    runtime::graph::RenderGraph& graph, const FrameInputs& inputs, const gpu::DenoisePush& push,
    std::initializer_list<Buffer> buffers) const {
  return pass_.add(graph, inputs, push, buffers,
                   {.x = push.width, .y = push.height, .threads = true});
}

}  // namespace lantern::lighting
