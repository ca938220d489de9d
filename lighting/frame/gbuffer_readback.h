// GBufferReadback: a Transfer pass copying the current frame's G-buffer images that describe
// where each pixel's surface is and how it moved (shared/gbuffer.h: position, emission_metallic,
// ids, motion; 16 bytes a texel each) into host-visible buffers, read back after the frame
// finished. What `lantern trade`'s motion-compensated flicker (motion_flicker.h) and the tests
// read; HeadlessSession::render hands it out.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <memory>
#include <vector>

#include "lighting/frame/frame_inputs.h"
#include "runtime/gpu/buffer.h"
#include "runtime/graph/render_graph.h"
#include "runtime/runtime_fwd.h"

namespace lantern::lighting {

// Host copies of one frame's G-buffer images, row-major from the top-left (shared/gbuffer.h).
struct GBufferTexels {
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  std::vector<glm::vec4> position;  // xyz world position, w view depth (0: sky)
  std::vector<glm::vec4> emission;  // rgb emitted radiance of the surface seen, a metallic
  std::vector<glm::uvec4> ids;      // x instance (gpu::kNoInstance: sky), y material, z primitive
  std::vector<glm::vec4> motion;    // xy to last frame's sample, zw the point's own motion
  std::size_t index(std::uint32_t x, std::uint32_t y) const { return std::size_t{y} * width + x; }
};

class GBufferReadback {
 public:
  explicit GBufferReadback(runtime::Device& device) : device_(device) {}

  // Adds pass "target.readback_gbuffer" copying `gbuffer`'s images (width x height) this frame.
  void add(runtime::graph::RenderGraph& graph, const GBufferHandles& gbuffer, std::uint32_t width,
           std::uint32_t height);
  // The copy of the last finished frame that add() was called in.
  GBufferTexels read() const;

 private:
  static constexpr int kImages = 4;  // position, emission_metallic, ids, motion
  runtime::Device& device_;
  std::vector<runtime::Buffer> buffers_;
  std::uint32_t width_ = 0;
  std::uint32_t height_ = 0;
};

}  // namespace lantern::lighting
