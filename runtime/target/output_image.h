// The target's output image: rgba32f at the render size, persistent across frames (imported
// into each frame's render graph), with the synchronisation state it was left in so the next
// frame's first write waits for the last frame's delivery (frames in flight share it safely).
#pragma once

#include <vulkan/vulkan.h>

#include <string>

#include "runtime/gpu/image.h"
#include "runtime/graph/render_graph.h"

namespace lantern::runtime {

class Device;

class OutputImage {
 public:
  static constexpr VkFormat kFormat = VK_FORMAT_R32G32B32A32_SFLOAT;

  OutputImage(Device& device, VkExtent2D extent, std::string name);

  // Imports the image; the graph leaves it in `delivered` (the delivery pass's use), which
  // becomes the initial state next frame (call commit() once the frame was recorded).
  graph::ImageHandle import(graph::RenderGraph& graph, const graph::AccessState& delivered);
  void commit() { state_ = pending_; }
  // Replaces the image (new size); the caller has waited for the frames using the old one.
  void resize(VkExtent2D extent);

  const Image& image() const { return image_; }
  VkExtent2D extent() const { return image_.extent(); }
  const graph::AccessState& state() const { return state_; }

 private:
  Device& device_;
  std::string name_;
  Image image_;
  graph::AccessState state_{};  // NONE/UNDEFINED: never used
  graph::AccessState pending_{};
};

}  // namespace lantern::runtime
