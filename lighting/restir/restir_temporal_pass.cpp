// restir.temporal: declares the pass and binds its resources by name
// (header: restir_temporal_pass.h).
#include "lighting/restir/restir_temporal_pass.h"

#include "lighting/restir/restir_pass_common.h"
#include "runtime/gpu/bindings.h"

namespace lantern::lighting {

using runtime::graph::Access;
using namespace restir_detail;

RestirTemporalPass::RestirTemporalPass(runtime::Device& device, runtime::ShaderLibrary& shaders)
    : pipeline_(device, shaders.load("restir/restir_temporal.comp"),
                runtime::ComputePipelineDesc{.name = "restir.temporal", .constants = {}}) {}

RestirTemporalPass::Output RestirTemporalPass::add(runtime::graph::RenderGraph& graph,
                                                   const FrameInputs& inputs,
                                                   const gpu::RestirPush& push,
                                                   const Input& input) const {
  struct Data {
    SceneHandles scene;
    GBufferHandles gbuffer;
    Input in;
    Output out;
  };
  const Data& data = graph.add_pass<Data>(
      "restir.temporal", runtime::graph::PassKind::Compute,
      [&](runtime::graph::PassBuilder& b, Data& d) {
        d.scene = inputs.scene_handles;
        d.gbuffer = inputs.gbuffer;
        d.in = input;
        d.scene.declare_reads(b, pipeline_);
        d.gbuffer.declare_reads(b, pipeline_);
        b.read(input.surfaces, Access::StorageRead);
        b.read(input.reservoirs_in, Access::StorageRead);
        // Without history the shader does not read the history bindings: this frame's surfaces
        // and reservoirs stand in (already declared reads).
        if (input.surfaces_history) b.read(input.surfaces_history, Access::StorageRead);
        if (input.reservoirs_history) b.read(input.reservoirs_history, Access::StorageRead);
        d.out.reservoirs = b.write(input.reservoirs_out, Access::StorageWrite);
        d.out.status = b.write(input.status, Access::StorageWrite);
      },
      [this, push](runtime::graph::PassContext& ctx, const Data& d) {
        const bool history = d.in.surfaces_history && d.in.reservoirs_history;
        runtime::Bindings b(pipeline_);
        d.scene.bind(b, ctx);
        d.gbuffer.bind(b, ctx);
        bind_buffer(b, ctx, "restir_surfaces", d.in.surfaces);
        bind_buffer(b, ctx, "reservoirs_in", d.in.reservoirs_in);
        bind_buffer(b, ctx, "surfaces_history", history ? d.in.surfaces_history : d.in.surfaces);
        bind_buffer(b, ctx, "reservoirs_history",
                    history ? d.in.reservoirs_history : d.in.reservoirs_in);
        bind_buffer(b, ctx, "reservoirs_out", d.out.reservoirs);
        bind_buffer(b, ctx, "temporal_status", d.out.status);
        gpu::RestirPush p = push;
        if (!history) p.lights.w &= ~gpu::kRestirFlagHistoryValid;
        pipeline_.bind(ctx.cmd(), b);
        pipeline_.push_constants(ctx.cmd(), p);
        pipeline_.dispatch(ctx.cmd(), tile_count(p.frame.x, p.frame.y));
      });
  return data.out;
}

}  // namespace lantern::lighting
