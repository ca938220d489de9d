// ShaderPass: declare and bind one compute pass by its shader's names (shader_pass.h).
#include "lighting/frame/shader_pass.h"

#include <cstddef>
#include <utility>

#include "runtime/gpu/bindings.h"
#include "runtime/gpu/shader_library.h"
#include "runtime/graph/pass_context.h"

namespace lantern::lighting {

using runtime::graph::Access;
using runtime::graph::BufferHandle;

namespace {
// Whether the shader reads buffer `name` through a texel view (a utextureBuffer) rather than as
// a storage buffer: the shader's declaration decides, the graph supplies the view.
bool reads_texels(const runtime::ComputePipeline& pipeline, const char* name) {
  const runtime::DescriptorBinding* binding = pipeline.find_binding(name);
  return binding != nullptr && binding->type == VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER;
}
}  // namespace

ShaderPass::ShaderPass(runtime::Device& device, runtime::ShaderLibrary& shaders, std::string name,
                       const std::string& shader, std::string_view variant,
                       runtime::SpecConstants constants)
    : name_(std::move(name)),
      pipeline_(device, shaders.load(shader, variant),
                runtime::ComputePipelineDesc{.name = name_, .constants = std::move(constants)}) {}

std::vector<BufferHandle> ShaderPass::add_bytes(runtime::graph::RenderGraph& graph,
                                                const FrameInputs& inputs, const PushBytes& push,
                                                std::initializer_list<ShaderPassBuffer> buffers,
                                                ShaderPassDispatch dispatch) const {
  struct Data {
    SceneHandles scene;
    GBufferHandles gbuffer;
    std::vector<ShaderPassBuffer> buffers;  // handles: the versions this pass reads or writes
    std::vector<bool> texels;  // per buffer: read through a texel view (reads_texels)
  };
  const Data& data = graph.add_pass<Data>(
      name_, runtime::graph::PassKind::Compute,
      [&](runtime::graph::PassBuilder& b, Data& d) {
        d.scene = inputs.scene_handles;
        d.gbuffer = inputs.gbuffer;
        d.scene.declare_reads(b, pipeline_);
        d.gbuffer.declare_reads(b, pipeline_);
        for (ShaderPassBuffer buffer : buffers) {
          bool texels = false;
          if (buffer.use == ShaderPassBuffer::Write) {
            buffer.handle = b.write(buffer.handle, Access::StorageWrite);
          } else if (buffer.use == ShaderPassBuffer::ReadWrite) {
            buffer.handle = b.write(buffer.handle, Access::StorageReadWrite);
          } else {
            // A handle read under two names is declared once per way it is read.
            texels = reads_texels(pipeline_, buffer.name);
            bool declared = false;
            for (std::size_t i = 0; i < d.buffers.size(); ++i) {
              declared = declared || (d.buffers[i].use == ShaderPassBuffer::Read &&
                                      d.buffers[i].handle == buffer.handle && d.texels[i] == texels);
            }
            if (!declared) {
              b.read(buffer.handle, texels ? Access::UniformTexelRead : Access::StorageRead);
            }
          }
          d.buffers.push_back(buffer);
          d.texels.push_back(texels);
        }
      },
      [this, push, dispatch](runtime::graph::PassContext& ctx, const Data& d) {
        runtime::Bindings b(pipeline_);
        d.scene.bind(b, ctx);
        d.gbuffer.bind(b, ctx);
        for (std::size_t i = 0; i < d.buffers.size(); ++i) {
          const ShaderPassBuffer& buffer = d.buffers[i];
          if (d.texels[i]) {
            b.texel_buffer(buffer.name, ctx.texel_view(buffer.handle));
          } else {
            b.buffer(buffer.name, ctx.buffer(buffer.handle), 0, VK_WHOLE_SIZE);
          }
        }
        pipeline_.bind(ctx.cmd(), b);
        pipeline_.push_constants(ctx.cmd(), push.data.data(), push.size);
        if (dispatch.threads) {
          pipeline_.dispatch_threads(ctx.cmd(), dispatch.x, dispatch.y);
        } else {
          pipeline_.dispatch(ctx.cmd(), dispatch.x, dispatch.y);
        }
      });
  std::vector<BufferHandle> written;
  for (const ShaderPassBuffer& buffer : data.buffers) {
    if (buffer.use != ShaderPassBuffer::Read) written.push_back(buffer.handle);
  }
  return written;
}

}  // namespace lantern::lighting
