// Upscaler: upscale.temporal's resources and push constants (upscaler.h).
#include "lighting/upscale/upscaler.h"

#include "lighting/frame/tile_order.h"
#include "runtime/gpu/bindings.h"
#include "runtime/gpu/shader_library.h"
#include "runtime/graph/pass_context.h"

namespace lantern::lighting {

using runtime::graph::Access;
using runtime::graph::BufferHandle;

Upscaler::Upscaler(runtime::Device& device, runtime::ShaderLibrary& shaders)
    : pipeline_(device, shaders.load("upscale/upscale_temporal.comp"),
                runtime::ComputePipelineDesc{
                    .name = "upscale.temporal",
                    .constants = pixel_group_constants(device)}) {}

gpu::UpscalePush Upscaler::make_push(const FrameInputs& inputs, std::uint32_t out_width,
                                     std::uint32_t out_height, glm::vec2 jitter) {
  gpu::UpscalePush p{};
  p.in_width = inputs.width;
  p.in_height = inputs.height;
  p.out_width = out_width;
  p.out_height = out_height;
  const bool same = inputs.width == out_width && inputs.height == out_height;
  p.history_weight = same && jitter == glm::vec2(0.0f) ? 0.0f : kHistoryWeight;
  p.jitter = jitter;
  return p;
}

BufferHandle Upscaler::add_pass(runtime::graph::RenderGraph& graph, const FrameInputs& inputs,
                                BufferHandle hdr, std::uint32_t out_width, std::uint32_t out_height,
                                glm::vec2 jitter) const {
  gpu::UpscalePush push = make_push(inputs, out_width, out_height, jitter);
  BufferHandle out = graph.create_history_buffer(
      "upscale.color", {VkDeviceSize{out_width} * out_height * 4 * sizeof(float)});
  const BufferHandle history = graph.history(out);
  if (history.valid()) push.flags |= gpu::kUpscaleFlagHistoryValid;
  struct Data {
    runtime::graph::ImageHandle motion;
    BufferHandle hdr, history, out;
  };
  const Data& data = graph.add_pass<Data>(
      "upscale.temporal", runtime::graph::PassKind::Compute,
      [&](runtime::graph::PassBuilder& b, Data& d) {
        d.motion = inputs.gbuffer.motion;
        b.read(d.motion, Access::StorageRead);
        d.hdr = hdr;
        // Both read through texel views (lib/texel_records.glsl). Without history this frame's
        // input stands in (not read: the flag is clear).
        b.read(hdr, Access::UniformTexelRead);
        d.history = history.valid() ? history : hdr;
        if (history.valid()) b.read(history, Access::UniformTexelRead);
        d.out = b.write(out, Access::StorageWrite);
      },
      [this, push](runtime::graph::PassContext& ctx, const Data& d) {
        pipeline_.bind(ctx.cmd(), runtime::Bindings(pipeline_)
                                      .image_view("gbuffer_motion", ctx.view(d.motion),
                                                  VK_IMAGE_LAYOUT_GENERAL)
                                      .texel_buffer("hdr_in", ctx.texel_view(d.hdr))
                                      .texel_buffer("history", ctx.texel_view(d.history))
                                      .buffer("hdr_out", ctx.buffer(d.out), 0, VK_WHOLE_SIZE));
        pipeline_.push_constants(ctx.cmd(), push);
        pipeline_.dispatch_threads(ctx.cmd(), push.out_width, push.out_height);
      });
  return data.out;
}

}  // namespace lantern::lighting
