// DenoisePass: one denoise.* compute pass — its pipeline (shaders/denoise/denoise_<stage>.comp,
// named "denoise.<stage>"), the scene buffers and G-buffer images its shader uses (declared and
// bound from the shader's reflection: SceneHandles, GBufferHandles), its own buffers by GLSL
// name, the push constants, one thread per pixel. What each stage reads and writes is listed
// where Denoiser adds it (denoiser.cpp) and in its shader's header.
#pragma once

#include <initializer_list>
#include <string>
#include <vector>

#include "lighting/frame/frame_inputs.h"
#include "runtime/gpu/compute_pipeline.h"
#include "runtime/runtime_fwd.h"
#include "shared/denoise.h"

namespace lantern::lighting {

class DenoisePass {
 public:
  struct Buffer {
    const char* name;
    runtime::graph::BufferHandle handle;
    enum Use { Read, Write } use = Read;  // Write: every pixel written, nothing read
  };

  DenoisePass(runtime::Device& device, runtime::ShaderLibrary& shaders, const std::string& stage);

  // Adds the pass; returns the new version of each Write buffer, in `buffers` order.
  std::vector<runtime::graph::BufferHandle> add(runtime::graph::RenderGraph& graph,
                                                const FrameInputs& inputs,
                                                const gpu::DenoisePush& push,
                                                std::initializer_list<Buffer> buffers) const;

  const runtime::ComputePipeline& pipeline() const { return pipeline_; }

 private:
  std::string name_;
  runtime::ComputePipeline pipeline_;
};

}  // namespace lantern::lighting
