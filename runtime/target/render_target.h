// RenderTarget: where a frame ends up, behind one interface so the render loop does not care
// whether it has a window (swapchain, present) or none (offscreen image read back to the host).
//
//   while (running) {
//     auto frame = target.begin_frame();
//     if (!frame) continue;                               // skip (minimised, out of date)
//     graph.begin_frame();
//     graph::ImageHandle out = target.import_output(graph, *frame);
//     out = /* passes writing `out` (rgba32f, frame->render_extent, linear display values) */;
//     target.add_delivery(graph, *frame, out);            // target.present or target.readback
//     graph.bake(executor.compile_options());
//     executor.record(graph, frame->cmd);
//     graph.end_frame();
//     target.end_frame(*frame);                           // submit (+ present)
//   }
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>
#include <optional>

#include "runtime/graph/render_graph.h"

namespace lantern::runtime {

struct TargetFrame {
  VkCommandBuffer cmd = VK_NULL_HANDLE;  // recording; end_frame() ends and submits it
  std::uint32_t slot = 0;                // frame-in-flight slot; per-slot resources are free
  std::uint64_t index = 0;               // frames begun so far (0 for the first)
  VkExtent2D render_extent{};            // size of the output image
};

class RenderTarget {
 public:
  virtual ~RenderTarget() = default;

  // Waits until the next frame slot is free and, for a window, acquires a swapchain image.
  // nullopt: no frame now (window minimised, swapchain could not be acquired): skip rendering.
  virtual std::optional<TargetFrame> begin_frame() = 0;
  // The target's output image (rgba32f, render_extent) imported into `graph` for this frame.
  // Its contents are undefined at the start of a frame: write every pixel.
  virtual graph::ImageHandle import_output(graph::RenderGraph& graph, const TargetFrame& frame) = 0;
  // Adds the pass that takes `output` (its latest version) to the screen or the host.
  virtual void add_delivery(graph::RenderGraph& graph, const TargetFrame& frame,
                            graph::ImageHandle output) = 0;
  // Submits frame.cmd (the baked graph recorded into it) and presents when there is a window.
  virtual void end_frame(const TargetFrame& frame) = 0;

  virtual VkExtent2D render_extent() const = 0;
  virtual std::uint32_t frames_in_flight() const = 0;
};

}  // namespace lantern::runtime
