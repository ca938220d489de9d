// restir.shade: declares the pass and binds its resources by name (header: restir_shade_pass.h).
#include "lighting/restir/restir_shade_pass.h"

#include "lighting/restir/restir_pass_common.h"
#include "runtime/gpu/bindings.h"

namespace lantern::lighting {

using runtime::graph::Access;
using runtime::graph::BufferHandle;
using namespace restir_detail;

RestirShadePass::RestirShadePass(runtime::Device& device, runtime::ShaderLibrary& shaders,
                                 VisibilityBackend visibility)
    : pipeline_(device, shaders.load("restir/restir_shade.comp", visibility_variant(visibility)),
                runtime::ComputePipelineDesc{.name = "restir.shade", .constants = {}}) {}

BufferHandle RestirShadePass::add(runtime::graph::RenderGraph& graph, const FrameInputs& inputs,
                                  const gpu::RestirPush& push, BufferHandle surfaces,
                                  BufferHandle reservoirs, BufferHandle status,
                                  BufferHandle hdr) const {
  struct Data {
    SceneHandles scene;
    GBufferHandles gbuffer;
    BufferHandle surfaces;
    BufferHandle reservoirs;
    BufferHandle status;
    BufferHandle hdr;
  };
  const Data& data = graph.add_pass<Data>(
      "restir.shade", runtime::graph::PassKind::Compute,
      [&](runtime::graph::PassBuilder& b, Data& d) {
        d.scene = inputs.scene_handles;
        d.gbuffer = inputs.gbuffer;
        d.surfaces = surfaces;
        d.reservoirs = reservoirs;
        d.status = status;
        d.scene.declare_reads(b, pipeline_);
        d.gbuffer.declare_reads(b, pipeline_);
        b.read(surfaces, Access::StorageRead);
        b.read(reservoirs, Access::StorageRead);
        b.read(status, Access::StorageRead);
        d.hdr = b.write(hdr, Access::StorageWrite);
      },
      [this, push](runtime::graph::PassContext& ctx, const Data& d) {
        runtime::Bindings b(pipeline_);
        d.scene.bind(b, ctx);
        d.gbuffer.bind(b, ctx);
        bind_buffer(b, ctx, "restir_surfaces", d.surfaces);
        bind_buffer(b, ctx, "reservoirs_in", d.reservoirs);
        bind_buffer(b, ctx, "temporal_status", d.status);
        bind_buffer(b, ctx, "hdr", d.hdr);
        pipeline_.bind(ctx.cmd(), b);
        pipeline_.push_constants(ctx.cmd(), push);
        pipeline_.dispatch(ctx.cmd(), tile_count(push.frame.x, push.frame.y));
      });
  return data.hdr;
}

}  // namespace lantern::lighting
