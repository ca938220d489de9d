// The pass of the one-pass integrators (integrators.baseline, integrators.reference): a compute
// pass over shuffled tiles (lighting/frame/tile_order.h) that reads the G-buffer's position,
// normal, emission/metallic and ids images and every scene buffer (GpuScene::bind, by name), and
// writes linear radiance into `hdr` (the shader's "radiance" buffer). The caller fills the push
// constants, tile_stride included.
#pragma once

#include <cstdint>
#include <string_view>

#include "lighting/frame/frame_inputs.h"
#include "lighting/scene/gpu_scene.h"
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
    runtime::graph::BufferHandle hdr;
    ImageHandle position, normal, emission, ids;
  };
  const GpuScene* scene = inputs.scene;
  const Data& data = graph.add_pass<Data>(
      name, runtime::graph::PassKind::Compute,
      [&](runtime::graph::PassBuilder& b, Data& d) {
        inputs.scene_handles.declare_reads(b);
        d.position = inputs.gbuffer.position;
        d.normal = inputs.gbuffer.normal;
        d.emission = inputs.gbuffer.emission_metallic;
        d.ids = inputs.gbuffer.ids;
        for (ImageHandle h : {d.position, d.normal, d.emission, d.ids}) {
          b.read(h, Access::StorageRead);
        }
        d.hdr = b.write(hdr, Access::StorageWrite);
      },
      [&pipeline, scene, push, tiles](runtime::graph::PassContext& ctx, const Data& d) {
        runtime::Bindings bindings(pipeline);
        scene->bind(bindings);
        bindings.buffer("radiance", ctx.buffer(d.hdr), 0, VK_WHOLE_SIZE)
            .image_view("gbuffer_position", ctx.view(d.position), VK_IMAGE_LAYOUT_GENERAL)
            .image_view("gbuffer_normal", ctx.view(d.normal), VK_IMAGE_LAYOUT_GENERAL)
            .image_view("gbuffer_emission_metallic", ctx.view(d.emission), VK_IMAGE_LAYOUT_GENERAL)
            .image_view("gbuffer_ids", ctx.view(d.ids), VK_IMAGE_LAYOUT_GENERAL);
        pipeline.bind(ctx.cmd(), bindings);
        pipeline.push_constants(ctx.cmd(), push);
        pipeline.dispatch(ctx.cmd(), tiles);
      });
  return data.hdr;
}

}  // namespace lantern::lighting
