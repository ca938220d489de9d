// restir.spatial: declares one spatial pass and binds its resources by name
// (header: restir_spatial_pass.h).
#include "lighting/restir/restir_spatial_pass.h"

#include "lighting/restir/restir_pass_common.h"
#include "runtime/gpu/bindings.h"

namespace lantern::lighting {

using runtime::graph::Access;
using runtime::graph::BufferHandle;
using namespace restir_detail;

RestirSpatialPass::RestirSpatialPass(runtime::Device& device, runtime::ShaderLibrary& shaders)
    : pipeline_(device, shaders.load("restir/restir_spatial.comp"),
                runtime::ComputePipelineDesc{.name = "restir.spatial", .constants = {}}) {}

BufferHandle RestirSpatialPass::add(runtime::graph::RenderGraph& graph, const FrameInputs& inputs,
                                    const gpu::RestirPush& push, BufferHandle surfaces,
                                    BufferHandle reservoirs_in, BufferHandle reservoirs_out) const {
  struct Data {
    SceneHandles scene;
    BufferHandle surfaces;
    BufferHandle in;
    BufferHandle out;
  };
  const Data& data = graph.add_pass<Data>(
      "restir.spatial", runtime::graph::PassKind::Compute,
      [&](runtime::graph::PassBuilder& b, Data& d) {
        d.scene = inputs.scene_handles;
        d.surfaces = surfaces;
        d.in = reservoirs_in;
        d.scene.declare_reads(b, pipeline_);
        b.read(surfaces, Access::StorageRead);
        b.read(reservoirs_in, Access::StorageRead);
        d.out = b.write(reservoirs_out, Access::StorageWrite);
      },
      [this, push](runtime::graph::PassContext& ctx, const Data& d) {
        runtime::Bindings b(pipeline_);
        d.scene.bind(b, ctx);
        bind_buffer(b, ctx, "restir_surfaces", d.surfaces);
        bind_buffer(b, ctx, "reservoirs_in", d.in);
        bind_buffer(b, ctx, "reservoirs_out", d.out);
        pipeline_.bind(ctx.cmd(), b);
        pipeline_.push_constants(ctx.cmd(), push);
        pipeline_.dispatch(ctx.cmd(), tile_count(push.frame.x, push.frame.y));
      });
  return data.out;
}

}  // namespace lantern::lighting
