// HdrReadback: a Transfer pass copying an HDR buffer (width*height vec4 linear radiance) of the
// current graph frame into a host-visible buffer, read back after the frame finished as an
// image with frame.output's linear conventions (non-finite and negative channels 0, alpha 1).
// How a headless session returns the raw image beside the denoised output the target shows.
#pragma once

#include <cstdint>
#include <memory>

#include "runtime/gpu/buffer.h"
#include "runtime/graph/render_graph.h"
#include "runtime/image/image.h"
#include "runtime/runtime_fwd.h"

namespace lantern::lighting {

class HdrReadback {
 public:
  explicit HdrReadback(runtime::Device& device) : device_(device) {}

  // Adds pass "target.readback_raw" copying `hdr` (width x height) this frame.
  void add(runtime::graph::RenderGraph& graph, runtime::graph::BufferHandle hdr,
           std::uint32_t width, std::uint32_t height);
  // The copy of the last finished frame that add() was called in.
  runtime::ImageRGBA32F read() const;

 private:
  runtime::Device& device_;
  std::unique_ptr<runtime::Buffer> buffer_;
  std::uint32_t width_ = 0;
  std::uint32_t height_ = 0;
};

}  // namespace lantern::lighting
