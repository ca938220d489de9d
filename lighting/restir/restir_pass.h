// RestirPass: one restir.* compute pass, a ShaderPass (lighting/frame/shader_pass.h) of
// shaders/restir/restir_<stage>.comp named "restir.<stage>", with RestirPush and one workgroup per
// tile, in pixel_tile_origin's order (lighting/frame/tile_order.h): tiles of the device's pixel
// group shape (rows on CPU devices), 8x8 for restir.initial (restir_pass.cpp), over the image's
// pixels (restir.shade) or the reservoir grid's cells (the other stages: RestirPush's
// reservoir_stride). What
// each pass reads and writes is listed where RestirIntegrator adds it (restir_integrator.cpp)
// and in its shader's header.
#pragma once

#include <cstdint>
#include <initializer_list>
#include <string>
#include <vector>

#include "lighting/frame/frame_inputs.h"
#include "lighting/frame/shader_pass.h"
#include "lighting/visibility/visibility_backend.h"
#include "runtime/gpu/compute_pipeline.h"
#include "runtime/runtime_fwd.h"
#include "shared/restir.h"

namespace lantern::lighting {

class RestirPass {
 public:
  using Buffer = ShaderPassBuffer;

  // `stage`: "presample", "initial", "temporal", "spatial" or "shade"; `visibility` picks the
  // shader variant of the passes that trace (initial, shade).
  RestirPass(runtime::Device& device, runtime::ShaderLibrary& shaders, const std::string& stage,
             VisibilityBackend visibility = VisibilityBackend::Bvh);
  // Pass `name` running restir_<stage>.comp's shader variant `variant` (the host visibility
  // backend's restir.shade: "hostemit", and "hostresolve" as restir.shade_occluded).
  RestirPass(runtime::Device& device, runtime::ShaderLibrary& shaders, const std::string& name,
             const std::string& stage, std::string_view variant);

  // Adds the pass; returns the new version of each Write / ReadWrite buffer, in `buffers` order.
  // A handle may be read under two names (a stand-in). `workgroups`: 0 for one per tile of the
  // image (the push's tile_stride set for this pass's tiles), else that many (a pass over
  // something else than pixels: restir.presample).
  std::vector<runtime::graph::BufferHandle> add(runtime::graph::RenderGraph& graph,
                                                const FrameInputs& inputs,
                                                const gpu::RestirPush& push,
                                                std::initializer_list<Buffer> buffers,
                                                std::uint32_t workgroups = 0) const;

  const runtime::ComputePipeline& pipeline() const { return pass_.pipeline(); }

 private:
  ShaderPass pass_;
  bool over_cells_;  // dispatched over the reservoir grid, not the image
};

}  // namespace lantern::lighting
