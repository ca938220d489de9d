// Headless frames: record, submit, wait; target.readback copies the output to host memory.
#include "runtime/target/headless_target.h"

#include <fmt/format.h>

#include <cstring>

#include "engine/core/error.h"
#include "runtime/core/device.h"

namespace lantern::runtime {
namespace {

VkExtent2D checked_extent(const HeadlessTargetDesc& desc) {
  if (desc.width == 0 || desc.height == 0)
    throw InputError(
        fmt::format("headless target size {}x{} must be non-zero", desc.width, desc.height));
  return {desc.width, desc.height};
}

graph::AccessState readback_source_state() {
  return graph::access_state(graph::Access::TransferSrc, graph::PassKind::Transfer, true);
}

constexpr graph::AccessState kHostRead{VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT,
                                       VK_IMAGE_LAYOUT_UNDEFINED};

}  // namespace

HeadlessTarget::HeadlessTarget(Device& device, const HeadlessTargetDesc& desc)
    : device_(device),
      slots_(device, 1),
      output_(device, checked_extent(desc), "target.output"),
      readback_(device, {.size = VkDeviceSize{desc.width} * desc.height * 16,
                         .usage = 0,
                         .memory = MemoryUsage::Readback,
                         .name = "target.readback"}) {}

HeadlessTarget::~HeadlessTarget() = default;

std::optional<TargetFrame> HeadlessTarget::begin_frame() {
  slots_.wait(0);
  delivery_added_ = false;
  return TargetFrame{slots_.begin(0), 0, frame_index_++, output_.extent()};
}

graph::ImageHandle HeadlessTarget::import_output(graph::RenderGraph& graph, const TargetFrame&) {
  return output_.import(graph, readback_source_state());
}

void HeadlessTarget::add_delivery(graph::RenderGraph& graph, const TargetFrame&,
                                  graph::ImageHandle output) {
  graph::ImportInfo info;
  info.initial = kHostRead;
  info.final = kHostRead;
  const graph::BufferHandle buffer =
      graph.import_buffer("target.readback", readback_.handle(), {readback_.size()}, info);
  struct Data {
    graph::ImageHandle image;
    graph::BufferHandle buffer;
  };
  const VkExtent2D extent = output_.extent();
  graph.add_pass<Data>(
      "target.readback", graph::PassKind::Transfer,
      [&](graph::PassBuilder& b, Data& d) {
        b.read(output, graph::Access::TransferSrc);
        d.image = output;
        d.buffer = b.write(buffer, graph::Access::TransferDst);
        b.side_effect();
      },
      [extent](graph::PassContext& ctx, const Data& d) {
        VkBufferImageCopy region{};
        region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        region.imageExtent = {extent.width, extent.height, 1};
        vkCmdCopyImageToBuffer(ctx.cmd(), ctx.image(d.image), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                               ctx.buffer(d.buffer), 1, &region);
      });
  delivery_added_ = true;
}

void HeadlessTarget::end_frame(const TargetFrame& frame) {
  slots_.submit(frame.slot, VK_NULL_HANDLE, 0, VK_NULL_HANDLE);
  output_.commit();
  slots_.wait(frame.slot);
  if (delivery_added_) ++delivered_;
}

ImageRGBA32F HeadlessTarget::read_output() const {
  if (delivered_ == 0)
    throw RuntimeError("headless target: no frame with a delivery pass has finished yet");
  const VkExtent2D extent = output_.extent();
  ImageRGBA32F image(extent.width, extent.height);
  std::memcpy(image.pixels.data(), readback_.mapped(), image.pixels.size() * sizeof(float));
  return image;
}

}  // namespace lantern::runtime
