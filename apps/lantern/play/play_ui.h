// The play viewer's ImGui layer: an ImGui context fed from PlayInput (not from GLFW callbacks,
// so scripted input drives it too) and drawn by Lantern's own ImGui renderer through the render
// graph: `play.ui` (graphics pass, dynamic rendering) draws the draw lists into a transient
// rgba16f UI layer cleared to 0 (premultiplied "over" blending), then `play.ui_composite`
// (compute) lays it over the target's output image. Debian's libimgui Vulkan backend needs a
// VkRenderPass and records outside the graph, so it is not used.
//
// Vertices and indices go to a host-visible buffer per frame-in-flight slot (imported read-only
// into the graph); the font atlas (alpha, one byte per texel) is a host-visible storage buffer.
#pragma once

#include <array>
#include <cstdint>
#include <memory>

#include "runtime/gpu/buffer.h"
#include "runtime/gpu/compute_pipeline.h"
#include "runtime/gpu/graphics_pipeline.h"
#include "runtime/graph/render_graph.h"

struct ImGuiContext;

namespace lantern::runtime {
class Device;
class ShaderLibrary;
}  // namespace lantern::runtime

namespace lantern::app {

struct PlayInput;

class PlayUi {
 public:
  PlayUi(runtime::Device& device, runtime::ShaderLibrary& shaders, std::uint32_t slots);
  ~PlayUi();
  PlayUi(const PlayUi&) = delete;
  PlayUi& operator=(const PlayUi&) = delete;

  void warm_up();
  // Starts an ImGui frame of `width` x `height` pixels with this frame's input.
  void new_frame(const PlayInput& input, std::uint32_t width, std::uint32_t height, float dt);
  // True when ImGui wants the mouse / keyboard (the camera should ignore them).
  bool wants_mouse() const;
  bool wants_keyboard() const;
  // Ends the ImGui frame and adds play.ui + play.ui_composite over `target` (the output image,
  // `width` x `height`); `slot` is the frame-in-flight slot whose buffers are free. Returns the
  // target's new version.
  [[nodiscard]] runtime::graph::ImageHandle add_passes(runtime::graph::RenderGraph& graph,
                                                       runtime::graph::ImageHandle target,
                                                       std::uint32_t width, std::uint32_t height,
                                                       std::uint32_t slot);
  // Ends the ImGui frame without drawing (the panel is hidden).
  void end_frame_without_drawing();
  // Triangles drawn last frame (tests).
  std::uint32_t last_triangles() const { return last_triangles_; }

 private:
  runtime::Device& device_;
  ImGuiContext* context_ = nullptr;
  runtime::GraphicsPipeline draw_;
  runtime::ComputePipeline composite_;
  runtime::Buffer font_;
  std::uint32_t font_width_ = 0;
  std::uint32_t font_height_ = 0;
  std::vector<runtime::Buffer> vertices_;  // per slot
  std::vector<runtime::Buffer> indices_;   // per slot
  std::uint32_t last_triangles_ = 0;
  bool frame_open_ = false;
};

}  // namespace lantern::app
