// The pass of the one-pass integrators (integrators.baseline, integrators.reference): a compute
// pass over shuffled tiles (lighting/frame/tile_order.h) that reads the G-buffer images and scene
// buffers its shader uses (GBufferHandles / SceneHandles declare and bind them by name) and
// writes linear radiance into `hdr` (the shader's "radiance" buffer). The caller fills the push
// constants, tile_stride included.
#pragma once

#include <cstdint>
#include <string_view>

#include "lighting/frame/frame_inputs.h"
#include "runtime/gpu/bindings.h"
#include "runtime/gpu/compute_pipeline.h"
#include "runtime/graph/render_graph.h"

namespace lantern::lighting {

template <class Push>
runtime::graph::BufferHandle add_gbuffer_shading_pass(runtime::graph::RenderGraph& graph,
                                                      std::string_view name,
                                                      const runtime::ComputePipeline& pipeline,
                                                      const FrameInputs& inputs, const Push& push,
                                                      std::uint32_t tiles,
                                                      runtime::graph::BufferHandle hdr) {
  using runtime::graph::Access;
  using runtime::graph::ImageHandle;
  struct Data {
    SceneHandles scene;
    GBufferHandles gbuffer;
    runtime::graph::BufferHandle hdr;
  };
  const Data& data = graph.add_pass<Data>(
      name, runtime::graph::PassKind::Compute,
      [&](runtime::graph::PassBuilder& b, Data& d) {
        d.scene = inputs.scene_handles;
        d.gbuffer = inputs.gbuffer;
        d.scene.declare_reads(b, pipeline);
        d.gbuffer.declare_reads(b, pipeline);
        d.hdr = b.write(hdr, runtime::graph::Access::StorageWrite);
      },
      [&pipeline, push, tiles](runtime::graph::PassContext& ctx, const Data& d) {
        runtime::Bindings bindings(pipeline);
        d.scene.bind(bindings, ctx);
        d.gbuffer.bind(bindings, ctx);
        bindings.buffer("radiance", ctx.buffer(d.hdr), 0, VK_WHOLE_SIZE);
        pipeline.bind(ctx.cmd(), bindings);
        pipeline.push_constants(ctx.cmd(), push);
        pipeline.dispatch(ctx.cmd(), tiles);
      });
  return data.hdr;
}

}  // namespace lantern::lighting
