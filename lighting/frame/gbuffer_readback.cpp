// GBufferReadback (gbuffer_readback.h).
#include "lighting/frame/gbuffer_readback.h"

#include <array>
#include <cstring>

#include "engine/core/error.h"
#include "runtime/graph/pass_context.h"

namespace lantern::lighting {

void GBufferReadback::add(runtime::graph::RenderGraph& graph, const GBufferHandles& gbuffer,
                          std::uint32_t width, std::uint32_t height) {
  const VkDeviceSize bytes = VkDeviceSize{width} * height * 16;
  if (buffers_.empty() || buffers_.front().size() < bytes) {
    buffers_.clear();
    for (const char* name : {"target.readback_position", "target.readback_emission",
                             "target.readback_ids", "target.readback_motion"}) {
      buffers_.emplace_back(device_, runtime::BufferDesc{.size = bytes,
                                                         .usage = VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                                         .memory = runtime::MemoryUsage::Readback,
                                                         .name = name});
    }
  }
  width_ = width;
  height_ = height;
  struct Copy {
    std::array<runtime::graph::ImageHandle, kImages> images;
    std::array<runtime::graph::BufferHandle, kImages> buffers;
  };
  graph.add_pass<Copy>(
      "target.readback_gbuffer", runtime::graph::PassKind::Transfer,
      [&](runtime::graph::PassBuilder& b, Copy& d) {
        runtime::graph::ImportInfo host_read;
        host_read.final = runtime::graph::AccessState{
            VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT, VK_IMAGE_LAYOUT_UNDEFINED};
        d.images = {gbuffer.position, gbuffer.emission_metallic, gbuffer.ids, gbuffer.motion};
        for (int i = 0; i < kImages; ++i) {
          b.read(d.images[i], runtime::graph::Access::TransferSrc);
          d.buffers[i] = b.write(
              graph.import_buffer(buffers_[i].name(), buffers_[i].handle(), {bytes}, host_read),
              runtime::graph::Access::TransferDst);
        }
        b.side_effect();
      },
      [width, height](runtime::graph::PassContext& ctx, const Copy& d) {
        for (int i = 0; i < kImages; ++i) {
          VkBufferImageCopy region{};
          region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
          region.imageExtent = {width, height, 1};
          vkCmdCopyImageToBuffer(ctx.cmd(), ctx.image(d.images[i]),
                                 VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, ctx.buffer(d.buffers[i]), 1,
                                 &region);
        }
      });
}

GBufferTexels GBufferReadback::read() const {
  if (buffers_.empty()) throw RuntimeError("G-buffer readback: nothing was copied");
  GBufferTexels t;
  t.width = width_;
  t.height = height_;
  const std::size_t n = std::size_t{width_} * height_;
  t.position.resize(n);
  t.emission.resize(n);
  t.ids.resize(n);
  t.motion.resize(n);
  std::memcpy(t.position.data(), buffers_[0].mapped(), n * sizeof(glm::vec4));
  std::memcpy(t.emission.data(), buffers_[1].mapped(), n * sizeof(glm::vec4));
  std::memcpy(t.ids.data(), buffers_[2].mapped(), n * sizeof(glm::uvec4));
  std::memcpy(t.motion.data(), buffers_[3].mapped(), n * sizeof(glm::vec4));
  return t;
}

}  // namespace lantern::lighting
