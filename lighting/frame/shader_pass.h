// ShaderPass: one compute pass of the lighting module's own shaders — its pipeline, the scene
// buffers and G-buffer images its shader uses (declared and bound from the shader's reflection:
// SceneHandles, GBufferHandles), its own buffers by GLSL name, push constants and a dispatch.
// restir.* (lighting/restir/restir_pass.h) and denoise.* (lighting/denoise/denoise_pass.h) are
// ShaderPasses with their push constants and dispatch shapes.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <initializer_list>
#include <string>
#include <string_view>
#include <vector>

#include "lighting/frame/frame_inputs.h"
#include "runtime/gpu/compute_pipeline.h"
#include "runtime/runtime_fwd.h"

namespace lantern::lighting {

// A buffer of the pass's own, by the name its shader gives it.
struct ShaderPassBuffer {
  const char* name;
  runtime::graph::BufferHandle handle;
  // Write: every pixel written, nothing read; ReadWrite: read and updated in place.
  enum Use { Read, Write, ReadWrite } use = Read;
};

// How many invocations: workgroups x * y, or threads x * y rounded up to workgroups.
struct ShaderPassDispatch {
  std::uint32_t x = 1;
  std::uint32_t y = 1;
  bool threads = false;
};

class ShaderPass {
 public:
  // `name`: the pass and pipeline name ("restir.initial"); `shader`: its path in the library;
  // `constants`: its specialisation (a per-pixel pass's workgroup shape: tile_order.h).
  ShaderPass(runtime::Device& device, runtime::ShaderLibrary& shaders, std::string name,
             const std::string& shader, std::string_view variant = {},
             runtime::SpecConstants constants = {});

  // Adds the pass; returns the new version of each Write / ReadWrite buffer, in `buffers` order.
  // A handle may be read under two names (a stand-in).
  template <class Push>
  std::vector<runtime::graph::BufferHandle> add(runtime::graph::RenderGraph& graph,
                                                const FrameInputs& inputs, const Push& push,
                                                std::initializer_list<ShaderPassBuffer> buffers,
                                                ShaderPassDispatch dispatch) const {
    static_assert(sizeof(Push) <= kMaxPushBytes, "push constants exceed 128 bytes");
    PushBytes bytes{};
    std::memcpy(bytes.data.data(), &push, sizeof(Push));
    bytes.size = sizeof(Push);
    return add_bytes(graph, inputs, bytes, buffers, dispatch);
  }

  const runtime::ComputePipeline& pipeline() const { return pipeline_; }

 private:
  static constexpr std::size_t kMaxPushBytes = 128;  // Vulkan's guaranteed minimum
  struct PushBytes {
    std::array<std::byte, kMaxPushBytes> data;
    std::uint32_t size;
  };
  std::vector<runtime::graph::BufferHandle> add_bytes(
      runtime::graph::RenderGraph& graph, const FrameInputs& inputs, const PushBytes& push,
      std::initializer_list<ShaderPassBuffer> buffers, ShaderPassDispatch dispatch) const;

  std::string name_;
  runtime::ComputePipeline pipeline_;
};

}  // namespace lantern::lighting
