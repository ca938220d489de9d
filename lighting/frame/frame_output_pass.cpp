// frame.output (frame_output_pass.h).
#include "lighting/frame/frame_output_pass.h"

#include "frame/frame_output.h"
#include "runtime/gpu/bindings.h"

namespace lantern::lighting {

runtime::graph::ImageHandle add_frame_output_pass(runtime::graph::RenderGraph& graph,
                                                  const runtime::ComputePipeline& pipeline,
                                                  runtime::graph::BufferHandle hdr,
                                                  runtime::graph::ImageHandle target,
                                                  std::uint32_t width, std::uint32_t height,
                                                  float exposure) {
  struct Data {
    runtime::graph::BufferHandle hdr;
    runtime::graph::ImageHandle target;
  };
  const gpu::FrameOutputPush push{width, height, exposure, 0u};
  const Data& data = graph.add_pass<Data>(
      "frame.output", runtime::graph::PassKind::Compute,
      [&](runtime::graph::PassBuilder& b, Data& d) {
        d.hdr = hdr;
        b.read(hdr, runtime::graph::Access::StorageRead);
        d.target = b.write(target, runtime::graph::Access::StorageWrite);
      },
      [&pipeline, push](runtime::graph::PassContext& ctx, const Data& d) {
        pipeline.bind(ctx.cmd(),
                      runtime::Bindings(pipeline)
                          .buffer("hdr", ctx.buffer(d.hdr), 0, VK_WHOLE_SIZE)
                          .image_view("target", ctx.view(d.target), VK_IMAGE_LAYOUT_GENERAL));
        pipeline.push_constants(ctx.cmd(), push);
        pipeline.dispatch_threads(ctx.cmd(), push.width, push.height);
      });
  return data.target;
}

}  // namespace lantern::lighting
