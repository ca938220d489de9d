// The scene's GPU interface as one table: a row per scene buffer (slot = binding in
// shared/scene_bindings.h, graph name, shader name, texel view, access, what fills it). GpuScene
// creates, uploads and imports the buffers from the rows; SceneHandles (what every pass gets)
// declares the reads of, and binds by name, exactly the scene buffers a pipeline's shaders use
// (shaders/lib/scene_buffers.glsl declares them all once). A new technique's scene buffer is a
// slot, a row here (with its source in SceneBufferSources) and a block in scene_buffers.glsl.
#pragma once

#include <vulkan/vulkan.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "runtime/graph/handles.h"
#include "runtime/runtime_fwd.h"
#include "shared/environment.h"
#include "shared/scene.h"
#include "shared/scene_bindings.h"

namespace lantern::lighting {

struct SceneData;

// The CPU arrays the scene buffers are uploaded from (GpuScene fills it; SceneBufferRow::bytes
// picks one).
struct SceneBufferSources {
  const gpu::FrameConstants* frame_constants = nullptr;
  const SceneData* data = nullptr;
  const std::vector<std::uint32_t>* light_previous_to_current = nullptr;
  const gpu::GpuEnvironment* env_header = nullptr;
  std::span<const std::byte> env_texels;
  std::span<const std::byte> env_marginal;
  std::span<const std::byte> env_conditional;
};

struct SceneBufferRow {
  std::uint32_t slot;        // = its binding (shared/scene_bindings.h)
  const char* graph_name;    // render-graph resource and debug name ("scene.lights")
  const char* shader_name;   // storage-buffer name in GLSL (instance name, else block name)
  const char* texel_name;    // name of its rgba32ui uniform texel view in GLSL, or nullptr
  bool read_only;            // uploaded once at load; scene.upload never writes it
  std::span<const std::byte> (*bytes)(const SceneBufferSources&);
};

// Row i describes slot i.
extern const std::array<SceneBufferRow, gpu::kSceneBufferCount> kSceneBuffers;

// The scene's buffers in one frame's graph, indexed by slot (after scene.upload: what passes
// read), and the texel views of the buffers that have one.
struct SceneHandles {
  std::array<runtime::graph::BufferHandle, gpu::kSceneBufferCount> buffers{};
  std::array<VkBufferView, gpu::kSceneBufferCount> texel_views{};

  runtime::graph::BufferHandle& operator[](std::uint32_t slot) { return buffers[slot]; }
  runtime::graph::BufferHandle operator[](std::uint32_t slot) const { return buffers[slot]; }

  // Declares a read of every scene buffer `pipeline`'s shaders use: StorageRead for a storage
  // binding, UniformTexelRead for a texel view. lantern::RuntimeError naming the buffer when the
  // pipeline uses one whose handle is not valid here.
  void declare_reads(runtime::graph::PassBuilder& builder, const runtime::Pipeline& pipeline) const;
  // Binds every scene buffer (and texel view) the pipeline's shaders use, by name.
  void bind(runtime::Bindings& bindings, const runtime::graph::PassContext& ctx) const;
};

}  // namespace lantern::lighting
