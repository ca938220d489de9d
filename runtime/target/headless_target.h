// HeadlessTarget: renders into an offscreen output image of a fixed size and copies each frame
// to a host-visible buffer (pass target.readback); read_output() converts the last finished frame
// to an ImageRGBA32F. One frame in flight: end_frame() waits, so results are ready after it.
#pragma once

#include <memory>
#include <string>

#include "runtime/gpu/buffer.h"
#include "runtime/image/image.h"
#include "runtime/target/frame_slots.h"
#include "runtime/target/output_image.h"
#include "runtime/target/render_target.h"

namespace lantern::runtime {

class Device;

struct HeadlessTargetDesc {
  std::uint32_t width = 640;
  std::uint32_t height = 360;
};

class HeadlessTarget final : public RenderTarget {
 public:
  // InputError for a zero size.
  HeadlessTarget(Device& device, const HeadlessTargetDesc& desc);
  ~HeadlessTarget() override;

  std::optional<TargetFrame> begin_frame() override;
  graph::ImageHandle import_output(graph::RenderGraph& graph, const TargetFrame& frame) override;
  void add_delivery(graph::RenderGraph& graph, const TargetFrame& frame,
                    graph::ImageHandle output) override;
  void end_frame(const TargetFrame& frame) override;
  VkExtent2D render_extent() const override { return output_.extent(); }
  std::uint32_t frames_in_flight() const override { return 1; }

  // The last frame's output. RuntimeError when no delivered frame has finished yet.
  ImageRGBA32F read_output() const;
  std::uint64_t frames_delivered() const { return delivered_; }

 private:
  Device& device_;
  FrameSlots slots_;
  OutputImage output_;
  Buffer readback_;
  std::uint64_t frame_index_ = 0;
  std::uint64_t delivered_ = 0;
  bool delivery_added_ = false;
};

}  // namespace lantern::runtime
