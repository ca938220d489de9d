// RestirPass: one restir.* compute pass — its pipeline (shaders/restir/restir_<stage>.comp, named
// "restir.<stage>"), the scene buffers and G-buffer images its shader uses (declared and bound
// from the shader's reflection: SceneHandles, GBufferHandles), its own buffers by GLSL name, the
// push constants, and one workgroup per shuffled 8x8 tile (lighting/frame/tile_order.h). What
// each pass reads and writes is listed where RestirIntegrator adds it (restir_integrator.cpp)
// and in its shader's header.
#pragma once

#include <cstdint>
#include <initializer_list>
#include <string>
#include <vector>

#include "lighting/frame/frame_inputs.h"
#include "lighting/visibility/visibility_backend.h"
#include "runtime/gpu/compute_pipeline.h"
#include "runtime/runtime_fwd.h"
#include "shared/restir.h"

namespace lantern::lighting {

class RestirPass {
 public:
  // A buffer of the pass's own, by the name its shader gives it.
  struct Buffer {
    const char* name;
    runtime::graph::BufferHandle handle;
    // Write: every pixel written, nothing read; ReadWrite: read and updated in place.
    enum Use { Read, Write, ReadWrite } use = Read;
  };

  // `stage`: "presample", "initial", "temporal", "spatial" or "shade"; `visibility` picks the
  // shader variant of the passes that trace (initial, shade).
  RestirPass(runtime::Device& device, runtime::ShaderLibrary& shaders, const std::string& stage,
             VisibilityBackend visibility = VisibilityBackend::Bvh);

  // Adds the pass; returns the new version of each Write buffer, in `buffers` order. A handle may
  // be read under two names (a stand-in). `workgroups`: 0 for one per shuffled tile of the image,
  // else that many (a pass over something else than pixels: restir.presample).
  std::vector<runtime::graph::BufferHandle> add(runtime::graph::RenderGraph& graph,
                                                const FrameInputs& inputs,
                                                const gpu::RestirPush& push,
                                                std::initializer_list<Buffer> buffers,
                                                std::uint32_t workgroups = 0) const;

  const runtime::ComputePipeline& pipeline() const { return pipeline_; }

 private:
  std::string name_;
  runtime::ComputePipeline pipeline_;
};

}  // namespace lantern::lighting
