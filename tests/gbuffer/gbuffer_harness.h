// Runs the gbuffer pass on its own for tests and the benchmark: the scene records of a SceneData
// in device buffers imported into a render graph, frame constants per frame, optional read-back
// of every G-buffer image through a Transfer pass, and GPU timings per pass. With
// GBufferMethod::Host it builds the host visibility (Embree) over the scene's BVH meshes at the
// instances' transforms (set_instances does not move them: tests move only previous transforms).
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "lighting/gbuffer/gbuffer_pass.h"
#include "lighting/scene/scene_data.h"
#include "lighting/visibility/host_visibility.h"
#include "runtime/gpu/buffer.h"
#include "runtime/gpu/gpu_timer.h"
#include "runtime/graph/graph_executor.h"
#include "runtime/graph/render_graph.h"
#include "shared/scene.h"

namespace lantern::runtime {
class ShaderLibrary;
}

namespace lantern::test {

// Host copies of the G-buffer images, row-major from the top-left (albedo converted from half).
struct GBufferImages {
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  std::vector<glm::vec4> position, normal, albedo_roughness, emission_metallic, motion;
  std::vector<glm::uvec4> ids;

  std::size_t index(std::uint32_t x, std::uint32_t y) const { return std::size_t{y} * width + x; }
};

class GBufferHarness {
 public:
  GBufferHarness(runtime::Device& device, runtime::ShaderLibrary& shaders,
                 const lighting::SceneData& scene,
                 const lighting::GBufferPassOptions& options = {});

  // Replaces the instance records (e.g. with different previous transforms).
  void set_instances(std::span<const gpu::GpuInstance> instances);
  void warm_up() { pass_.warm_up(); }

  // One frame at constants.frame.xy; with `read_back`, the images come back.
  std::optional<GBufferImages> render(const gpu::FrameConstants& constants, bool read_back);
  // GPU milliseconds of the last frame's pass `name` ("gbuffer", "gbuffer.draws"); -1 if absent.
  double last_ms(const std::string& name) const;

 private:
  runtime::Device& device_;
  lighting::GBufferPass pass_;
  // GBufferMethod::Host: Embree over the scene's BVH meshes at the instances' transforms.
  std::unique_ptr<lighting::HostVisibility> host_;
  std::vector<gpu::GpuInstance> instances_host_;
  runtime::Buffer frame_constants_, vertices_, indices_, materials_, instances_, textures_, texels_,
      vertex_tangents_, vertex_texcoords1_;
  std::vector<runtime::Buffer> readback_;
  std::uint32_t readback_width_ = 0, readback_height_ = 0;
  runtime::graph::RenderGraph graph_;
  runtime::graph::GraphExecutor executor_;
  runtime::GpuTimer timer_;
  std::vector<runtime::GpuTimer::Result> timings_;
};

}  // namespace lantern::test
