// HdrReadback (hdr_readback.h).
#include "lighting/frame/hdr_readback.h"

#include <cmath>
#include <cstring>

#include "engine/core/error.h"
#include "runtime/graph/pass_context.h"

namespace lantern::lighting {

void HdrReadback::add(runtime::graph::RenderGraph& graph, runtime::graph::BufferHandle hdr,
                      std::uint32_t width, std::uint32_t height) {
  const VkDeviceSize bytes = VkDeviceSize{width} * height * 4 * sizeof(float);
  if (!buffer_ || buffer_->size() < bytes) {
    buffer_ = std::make_unique<runtime::Buffer>(
        device_, runtime::BufferDesc{.size = bytes,
                                     .usage = VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                     .memory = runtime::MemoryUsage::Readback,
                                     .name = "frame.raw_readback"});
  }
  width_ = width;
  height_ = height;
  struct Copy {
    runtime::graph::BufferHandle src;
    runtime::graph::BufferHandle dst;
  };
  runtime::Buffer& host = *buffer_;
  graph.add_pass<Copy>(
      "target.readback_raw", runtime::graph::PassKind::Transfer,
      [&](runtime::graph::PassBuilder& b, Copy& d) {
        runtime::graph::ImportInfo host_read;
        host_read.final = runtime::graph::AccessState{
            VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT, VK_IMAGE_LAYOUT_UNDEFINED};
        d.src = hdr;
        b.read(hdr, runtime::graph::Access::TransferSrc);
        d.dst = b.write(graph.import_buffer(host.name(), host.handle(), {bytes}, host_read),
                        runtime::graph::Access::TransferDst);
        b.side_effect();
      },
      [bytes](runtime::graph::PassContext& ctx, const Copy& d) {
        const VkBufferCopy region{0, 0, bytes};
        vkCmdCopyBuffer(ctx.cmd(), ctx.buffer(d.src), ctx.buffer(d.dst), 1, &region);
      });
}

runtime::ImageRGBA32F HdrReadback::read() const {
  if (!buffer_) throw RuntimeError("hdr readback: nothing was copied");
  runtime::ImageRGBA32F image(width_, height_);
  std::memcpy(image.pixels.data(), buffer_->mapped(), image.pixels.size() * sizeof(float));
  for (std::size_t i = 0; i < image.pixels.size(); i += 4) {
    for (std::size_t c = 0; c < 3; ++c) {
      float& v = image.pixels[i + c];
      if (!std::isfinite(v) || v < 0.0f) v = 0.0f;
    }
    image.pixels[i + 3] = 1.0f;
  }
  return image;
}

}  // namespace lantern::lighting
