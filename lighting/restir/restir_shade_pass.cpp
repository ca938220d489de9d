// restir.shade: declares the pass and binds its resources by name (header: restir_shade_pass.h).
#include "lighting/restir/restir_shade_pass.h"

#include "lighting/restir/restir_pass_common.h"
#include "runtime/gpu/bindings.h"

namespace lantern::lighting {

using runtime::graph::Access;
using runtime::graph::BufferHandle;
using namespace restir_detail;

RestirShadePass::RestirShadePass(runtime::Device& device, runtime::ShaderLibrary& shaders)
    : pipeline_(device, shaders.load("restir/restir_shade.comp"),
                runtime::ComputePipelineDesc{.name = "restir.shade", .constants = {}}) {}

BufferHandle RestirShadePass::add(runtime::graph::RenderGraph& graph, const FrameInputs& inputs,
                                  const gpu::RestirPush& push, BufferHandle surfaces,
                                  BufferHandle reservoirs, BufferHandle status,
                                  BufferHandle hdr) const {
  struct Data {
    SceneHandles scene;
    runtime::graph::ImageHandle emission;
    runtime::graph::ImageHandle motion;
    BufferHandle surfaces;
    BufferHandle reservoirs;
    BufferHandle status;
    BufferHandle hdr;
  };
  const Data& data = graph.add_pass<Data>(
      "restir.shade", runtime::graph::PassKind::Compute,
      [&](runtime::graph::PassBuilder& b, Data& d) {
        d.scene = inputs.scene_handles;
        d.emission = inputs.gbuffer.emission_metallic;
        d.motion = inputs.gbuffer.motion;
        d.surfaces = surfaces;
        d.reservoirs = reservoirs;
        d.status = status;
        inputs.scene_handles.declare_reads(b);  // lights, frame constants, BVH (texel views)
        b.read(d.emission, Access::StorageRead);
        b.read(d.motion, Access::StorageRead);
        b.read(surfaces, Access::StorageRead);
        b.read(reservoirs, Access::StorageRead);
        b.read(status, Access::StorageRead);
        d.hdr = b.write(hdr, Access::StorageWrite);
      },
      [this, push, scene = inputs.scene](runtime::graph::PassContext& ctx, const Data& d) {
        runtime::Bindings b(pipeline_);
        bind_visibility(b, ctx, d.scene, scene);  // first: the graph's buffers below win
        bind_environment(b, ctx, d.scene);
        bind_buffer(b, ctx, "frame_constants", d.scene.frame_constants);
        bind_buffer(b, ctx, "scene_lights", d.scene.lights);
        bind_image(b, ctx, "gbuffer_emission_metallic", d.emission);
        bind_image(b, ctx, "gbuffer_motion", d.motion);
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
