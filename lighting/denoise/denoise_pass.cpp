// DenoisePass: declare and bind one denoise.* pass by name (denoise_pass.h).
#include "lighting/denoise/denoise_pass.h"

#include <algorithm>

#include "runtime/gpu/bindings.h"
#include "runtime/gpu/shader_library.h"
#include "runtime/graph/pass_context.h"

namespace lantern::lighting {

using runtime::graph::Access;
using runtime::graph::BufferHandle;

DenoisePass::DenoisePass(runtime::Device& device, runtime::ShaderLibrary& shaders,
                         const std::string& stage)
    : name_("denoise." + stage),
      pipeline_(device, shaders.load("denoise/denoise_" + stage + ".comp"),
                runtime::ComputePipelineDesc{.name = name_, .constants = {}}) {}

std::vector<BufferHandle> DenoisePass::add(runtime::graph::RenderGraph& graph,
                                           const FrameInputs& inputs,
                                           const gpu::DenoisePush& push,
                                           std::initializer_list<Buffer> buffers) const {
  struct Data {
    SceneHandles scene;
    GBufferHandles gbuffer;
    std::vector<Buffer> buffers;
  };
  const Data& data = graph.add_pass<Data>(
      name_, runtime::graph::PassKind::Compute,
      [&](runtime::graph::PassBuilder& b, Data& d) {
        d.scene = inputs.scene_handles;
        d.gbuffer = inputs.gbuffer;
        d.scene.declare_reads(b, pipeline_);
        d.gbuffer.declare_reads(b, pipeline_);
        for (Buffer buffer : buffers) {
          if (buffer.use == Buffer::Write) {
            buffer.handle = b.write(buffer.handle, Access::StorageWrite);
          } else if (std::none_of(d.buffers.begin(), d.buffers.end(), [&](const Buffer& o) {
                       return o.use == Buffer::Read && o.handle == buffer.handle;
                     })) {
            b.read(buffer.handle, Access::StorageRead);
          }
          d.buffers.push_back(buffer);
        }
      },
      [this, push](runtime::graph::PassContext& ctx, const Data& d) {
        runtime::Bindings b(pipeline_);
        d.scene.bind(b, ctx);
        d.gbuffer.bind(b, ctx);
        for (const Buffer& buffer : d.buffers) {
          b.buffer(buffer.name, ctx.buffer(buffer.handle), 0, VK_WHOLE_SIZE);
        }
        pipeline_.bind(ctx.cmd(), b);
        pipeline_.push_constants(ctx.cmd(), push);
        pipeline_.dispatch_threads(ctx.cmd(), push.width, push.height);
      });
  std::vector<BufferHandle> written;
  for (const Buffer& buffer : data.buffers) {
    if (buffer.use != Buffer::Read) written.push_back(buffer.handle);
  }
  return written;
}

}  // namespace lantern::lighting
