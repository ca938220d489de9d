// restir.initial (shaders/restir/restir_initial.comp): packs the G-buffer into per-pixel
// RestirSurfaces and draws each pixel's initial reservoir from light (and BSDF) candidates.
// Reads: G-buffer (position, normal, albedo_roughness, emission_metallic, ids), scene buffers
// (frame constants, materials, instances, lights, alias table, BVH). Writes: `surfaces` (this
// frame's version of the "restir.surfaces" history), `reservoirs` (the plan's output buffer).
// History: none read. Dispatch: one 8x8 workgroup per shuffled tile.
#pragma once

#include "lighting/frame/frame_inputs.h"
#include "runtime/gpu/compute_pipeline.h"
#include "runtime/gpu/shader_library.h"
#include "shared/restir.h"

namespace lantern::lighting {

class RestirInitialPass {
 public:
  RestirInitialPass(runtime::Device& device, runtime::ShaderLibrary& shaders,
                    VisibilityBackend visibility = VisibilityBackend::Bvh);
  const runtime::ComputePipeline& pipeline() const { return pipeline_; }

  struct Output {
    runtime::graph::BufferHandle surfaces;
    runtime::graph::BufferHandle reservoirs;
  };
  Output add(runtime::graph::RenderGraph& graph, const FrameInputs& inputs,
             const gpu::RestirPush& push, runtime::graph::BufferHandle surfaces,
             runtime::graph::BufferHandle reservoirs) const;

 private:
  runtime::ComputePipeline pipeline_;
};

}  // namespace lantern::lighting
