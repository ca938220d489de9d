// restir.temporal (shaders/restir/restir_temporal.comp): merges each pixel's reservoir with last
// frame's final reservoir at its reprojected pixel, after a disocclusion test and the light
// remap; M capped. Reads: `surfaces` (this frame), `reservoirs_in`, G-buffer motion, frame
// constants, lights, light_previous_to_current; history: last frame's "restir.surfaces" and
// "restir.reservoirs" (invalid handles = no history: every pixel keeps its own reservoir).
// Writes: `reservoirs_out`, `status` (uint per pixel, kRestirStatus*).
// Dispatch: one 8x8 workgroup per shuffled tile.
#pragma once

#include "lighting/frame/frame_inputs.h"
#include "runtime/gpu/compute_pipeline.h"
#include "runtime/gpu/shader_library.h"
#include "shared/restir.h"

namespace lantern::lighting {

class RestirTemporalPass {
 public:
  RestirTemporalPass(runtime::Device& device, runtime::ShaderLibrary& shaders);
  const runtime::ComputePipeline& pipeline() const { return pipeline_; }

  struct Input {
    runtime::graph::BufferHandle surfaces;
    runtime::graph::BufferHandle reservoirs_in;
    runtime::graph::BufferHandle surfaces_history;    // invalid: no history this frame
    runtime::graph::BufferHandle reservoirs_history;  // invalid: no history this frame
    runtime::graph::BufferHandle reservoirs_out;
    runtime::graph::BufferHandle status;
  };
  struct Output {
    runtime::graph::BufferHandle reservoirs;
    runtime::graph::BufferHandle status;
  };
  // push.lights.w must carry kRestirFlagHistoryValid exactly when both history handles are valid.
  Output add(runtime::graph::RenderGraph& graph, const FrameInputs& inputs,
             const gpu::RestirPush& push, const Input& input) const;

 private:
  runtime::ComputePipeline pipeline_;
};

}  // namespace lantern::lighting
