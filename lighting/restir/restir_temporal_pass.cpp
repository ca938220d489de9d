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
    runtime::graph::ImageHandle motion;
    Input in;
    Output out;
  };
  const Data& data = graph.add_pass<Data>(
      "restir.temporal", runtime::graph::PassKind::Compute,
      [&](runtime::graph::PassBuilder& b, Data& d) {
        d.scene = inputs.scene_handles;
        d.motion = inputs.gbuffer.motion;
        d.in = input;
        b.read(d.scene.frame_constants, Access::StorageRead);
        b.read(d.scene.lights, Access::StorageRead);
        b.read(d.scene.light_previous_to_current, Access::StorageRead);
        declare_environment_reads(b, d.scene);
        b.read(d.motion, Access::StorageRead);
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
        bind_buffer(b, ctx, "frame_constants", d.scene.frame_constants);
        bind_buffer(b, ctx, "scene_lights", d.scene.lights);
        bind_buffer(b, ctx, "light_remap", d.scene.light_previous_to_current);
        bind_environment(b, ctx, d.scene);
        bind_image(b, ctx, "gbuffer_motion", d.motion);
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
