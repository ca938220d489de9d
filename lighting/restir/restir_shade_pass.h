// restir.shade (shaders/restir/restir_shade.comp): one visibility ray per pixel towards the final
// reservoir's sample; writes emission + BRDF x Le x G x W (or a debug view) into hdr.
// Reads: `surfaces`, `reservoirs` (final), `status` (restir.temporal's), G-buffer
// emission_metallic and motion, frame constants, lights, BVH. Writes: hdr (vec4 per pixel).
// History: none. Dispatch: one 8x8 workgroup per shuffled tile.
#pragma once

#include "lighting/frame/frame_inputs.h"
#include "runtime/gpu/compute_pipeline.h"
#include "runtime/gpu/shader_library.h"
#include "shared/restir.h"

namespace lantern::lighting {

class RestirShadePass {
 public:
  RestirShadePass(runtime::Device& device, runtime::ShaderLibrary& shaders,
                  VisibilityBackend visibility = VisibilityBackend::Bvh);
  const runtime::ComputePipeline& pipeline() const { return pipeline_; }

  runtime::graph::BufferHandle add(runtime::graph::RenderGraph& graph, const FrameInputs& inputs,
                                   const gpu::RestirPush& push,
                                   runtime::graph::BufferHandle surfaces,
                                   runtime::graph::BufferHandle reservoirs,
                                   runtime::graph::BufferHandle status,
                                   runtime::graph::BufferHandle hdr) const;

 private:
  runtime::ComputePipeline pipeline_;
};

}  // namespace lantern::lighting
