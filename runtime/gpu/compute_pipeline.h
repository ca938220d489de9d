// A compute pipeline made from one reflected shader: layout from reflection, specialisation
// constants by name, local size known (after specialisation) so dispatch_threads() can round up.
#pragma once

#include <array>
#include <memory>
#include <span>
#include <string>

#include "runtime/gpu/pipeline.h"

namespace lantern::runtime {

struct ComputePipelineDesc {
  std::string name;  // debug name and timing key, e.g. "restir.initial"; default: the shader's name
  SpecConstants constants;
};

class ComputePipeline : public Pipeline {
 public:
  ComputePipeline(Device& device, std::shared_ptr<const ShaderCode> shader,
                  const ComputePipelineDesc& desc = {});
  ComputePipeline(ComputePipeline&&) noexcept = default;
  ~ComputePipeline() = default;

  // Workgroup size after specialisation (local_size_x_id etc. resolved).
  const std::array<std::uint32_t, 3>& local_size() const { return local_size_; }
  const ShaderCode& shader() const { return *shader_; }

  void dispatch(VkCommandBuffer cmd, std::uint32_t groups_x, std::uint32_t groups_y = 1,
                std::uint32_t groups_z = 1) const;
  // Enough workgroups to cover threads_x * threads_y * threads_z invocations.
  void dispatch_threads(VkCommandBuffer cmd, std::uint32_t threads_x, std::uint32_t threads_y = 1,
                        std::uint32_t threads_z = 1) const;
  // Runs the pipeline once with throw-away resources so the driver's JIT (lavapipe compiles at
  // first dispatch, PLATFORM.md) happens now, not inside the first timed frame.
  void warm_up() const;

 private:
  std::shared_ptr<const ShaderCode> shader_;
  std::array<std::uint32_t, 3> local_size_{1, 1, 1};
};

// Warms up several pipelines in one submission (see ComputePipeline::warm_up).
void warm_up(Device& device, std::span<const ComputePipeline* const> pipelines);

}  // namespace lantern::runtime
