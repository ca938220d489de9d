// restir.spatial (shaders/restir/restir_spatial.comp), run N times: merges each pixel's reservoir
// with up to k similar neighbours in a disk (more where history is short).
// Reads: `surfaces`, `reservoirs_in`, frame constants, lights. Writes: `reservoirs_out` (the
// plan's next buffer; the last pass writes the frame's final reservoirs). History: none.
// Dispatch: one 8x8 workgroup per shuffled tile.
#pragma once

#include "lighting/frame/frame_inputs.h"
#include "runtime/gpu/compute_pipeline.h"
#include "runtime/gpu/shader_library.h"
#include "shared/restir.h"

namespace lantern::lighting {

class RestirSpatialPass {
 public:
  RestirSpatialPass(runtime::Device& device, runtime::ShaderLibrary& shaders);
  const runtime::ComputePipeline& pipeline() const { return pipeline_; }

  // push.spatial.y is the pass index (seeds its random stream).
  runtime::graph::BufferHandle add(runtime::graph::RenderGraph& graph, const FrameInputs& inputs,
                                   const gpu::RestirPush& push,
                                   runtime::graph::BufferHandle surfaces,
                                   runtime::graph::BufferHandle reservoirs_in,
                                   runtime::graph::BufferHandle reservoirs_out) const;

 private:
  runtime::ComputePipeline pipeline_;
};

}  // namespace lantern::lighting
