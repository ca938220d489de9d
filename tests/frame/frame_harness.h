// Test harness: a FrameRenderer (baseline) with a HeadlessTarget, rendering one snapshot per call
// through the render graph and reading the linear HDR image back.
#pragma once

#include <memory>

#include "engine/world/frame_snapshot.h"
#include "lighting/frame/frame_renderer.h"
#include "lighting/integrators/integrator_registry.h"
#include "runtime/gpu/shader_library.h"
#include "runtime/graph/graph_executor.h"
#include "runtime/graph/render_graph.h"
#include "runtime/target/headless_target.h"

namespace lantern::test {

class FrameHarness {
 public:
  FrameHarness(runtime::Device& device, runtime::ShaderLibrary& shaders,
               std::shared_ptr<const Level> level, std::uint32_t width, std::uint32_t height)
      : renderer_(device, shaders, level,
                  lighting::make_integrator(device, shaders,
                                            {.name = "baseline"}),
                  width, height, 1),
        target_(device, {.width = width, .height = height}),
        executor_(device) {
    renderer_.warm_up();
  }

  runtime::ImageRGBA32F render(const FrameSnapshot& snapshot) {
    const auto frame = target_.begin_frame();
    graph_.begin_frame();
    const auto hdr = renderer_.add_frame(graph_, snapshot);
    const auto out =
        renderer_.add_output_pass(graph_, hdr, target_.import_output(graph_, *frame), 0.0f);
    target_.add_delivery(graph_, *frame, out);
    graph_.bake(executor_.compile_options());
    executor_.record(graph_, frame->cmd);
    graph_.end_frame();
    target_.end_frame(*frame);
    return target_.read_output();
  }

  lighting::FrameRenderer& renderer() { return renderer_; }

 private:
  lighting::FrameRenderer renderer_;
  runtime::HeadlessTarget target_;
  runtime::graph::RenderGraph graph_;
  runtime::graph::GraphExecutor executor_;
};

}  // namespace lantern::test
