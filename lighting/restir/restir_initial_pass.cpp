// restir.initial: declares the pass and binds its resources by name (header: restir_initial_pass.h).
#include "lighting/restir/restir_initial_pass.h"

#include "lighting/restir/restir_pass_common.h"
#include "runtime/gpu/bindings.h"

namespace lantern::lighting {

using runtime::graph::Access;
using runtime::graph::BufferHandle;
using namespace restir_detail;

RestirInitialPass::RestirInitialPass(runtime::Device& device, runtime::ShaderLibrary& shaders,
                                     VisibilityBackend visibility)
    : pipeline_(device, shaders.load("restir/restir_initial.comp", visibility_variant(visibility)),
                runtime::ComputePipelineDesc{.name = "restir.initial", .constants = {}}) {}

RestirInitialPass::Output RestirInitialPass::add(runtime::graph::RenderGraph& graph,
                                                 const FrameInputs& inputs,
                                                 const gpu::RestirPush& push,
                                                 BufferHandle surfaces,
                                                 BufferHandle reservoirs) const {
  struct Data {
    SceneHandles scene;
    GBufferHandles gbuffer;
    Output out;
  };
  const Data& data = graph.add_pass<Data>(
      "restir.initial", runtime::graph::PassKind::Compute,
      [&](runtime::graph::PassBuilder& b, Data& d) {
        d.scene = inputs.scene_handles;
        d.gbuffer = inputs.gbuffer;
        inputs.scene_handles.declare_reads(b, pipeline_);
        inputs.gbuffer.declare_reads(b, pipeline_);
        d.out.surfaces = b.write(surfaces, Access::StorageWrite);
        d.out.reservoirs = b.write(reservoirs, Access::StorageWrite);
      },
      [this, push](runtime::graph::PassContext& ctx, const Data& d) {
        runtime::Bindings b(pipeline_);
        d.scene.bind(b, ctx);
        d.gbuffer.bind(b, ctx);
        bind_buffer(b, ctx, "restir_surfaces", d.out.surfaces);
        bind_buffer(b, ctx, "reservoirs_out", d.out.reservoirs);
        pipeline_.bind(ctx.cmd(), b);
        pipeline_.push_constants(ctx.cmd(), push);
        pipeline_.dispatch(ctx.cmd(), tile_count(push.frame.x, push.frame.y));
      });
  return data.out;
}

}  // namespace lantern::lighting
