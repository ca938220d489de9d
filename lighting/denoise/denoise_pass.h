// DenoisePass: one denoise.* compute pass, a ShaderPass (lighting/frame/shader_pass.h) of
// shaders/denoise/denoise_<stage>.comp named "denoise.<stage>", with DenoisePush and one thread
// per pixel, or, for the à-trous stages (Threads::PixelPairs), one per pair of pixels
// push.step apart (denoise_atrous_pair_columns, shared/denoise.h). What each stage reads and
// writes is listed where Denoiser adds it (denoiser.cpp) and in its shader's header.
#pragma once

#include <initializer_list>
#include <string>
#include <vector>

#include "lighting/frame/frame_inputs.h"
#include "lighting/frame/shader_pass.h"
#include "runtime/gpu/compute_pipeline.h"
#include "runtime/runtime_fwd.h"
#include "shared/denoise.h"

namespace lantern::lighting {

class DenoisePass {
 public:
  using Buffer = ShaderPassBuffer;

  enum class Threads { Pixels, PixelPairs };

  DenoisePass(runtime::Device& device, runtime::ShaderLibrary& shaders, const std::string& stage,
              Threads threads = Threads::Pixels);

  // Adds the pass; returns the new version of each Write buffer, in `buffers` order.
  std::vector<runtime::graph::BufferHandle> add(runtime::graph::RenderGraph& graph,
                                                const FrameInputs& inputs,
                                                const gpu::DenoisePush& push,
                                                std::initializer_list<Buffer> buffers) const;

  const runtime::ComputePipeline& pipeline() const { return pass_.pipeline(); }

 private:
  ShaderPass pass_;
  Threads threads_;
};

}  // namespace lantern::lighting
