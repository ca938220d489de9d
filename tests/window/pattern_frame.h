// Test helper: one frame through any RenderTarget: the window_pattern compute pass writes the
// target's output image through the render graph, then the target's delivery pass runs.
#pragma once

#include <cstdint>

#include "runtime/gpu/bindings.h"
#include "runtime/gpu/compute_pipeline.h"
#include "runtime/graph/graph_executor.h"
#include "runtime/target/render_target.h"

namespace lantern::runtime::test {

struct PatternPush {
  std::uint32_t size[2];
  std::uint32_t frame;
  std::uint32_t pad;
};

// Returns false when the target gave no frame (skipped).
inline bool render_pattern_frame(RenderTarget& target, graph::RenderGraph& graph,
                                 graph::GraphExecutor& executor, const ComputePipeline& pattern,
                                 std::uint32_t pattern_frame) {
  const auto frame = target.begin_frame();
  if (!frame) return false;
  graph.begin_frame();
  const graph::ImageHandle output = target.import_output(graph, *frame);
  struct Data {
    graph::ImageHandle image;
  };
  const VkExtent2D extent = frame->render_extent;
  const Data& written = graph.add_pass<Data>(
      "test.pattern", graph::PassKind::Compute,
      [&](graph::PassBuilder& b, Data& d) {
        d.image = b.write(output, graph::Access::StorageWrite);
      },
      [&pattern, extent, pattern_frame](graph::PassContext& ctx, const Data& d) {
        pattern.bind(ctx.cmd(), Bindings(pattern).image_view("target", ctx.view(d.image),
                                                             VK_IMAGE_LAYOUT_GENERAL));
        pattern.push_constants(ctx.cmd(),
                               PatternPush{{extent.width, extent.height}, pattern_frame, 0});
        pattern.dispatch_threads(ctx.cmd(), extent.width, extent.height);
      });
  target.add_delivery(graph, *frame, written.image);
  graph.bake(executor.compile_options());
  executor.record(graph, frame->cmd);
  graph.end_frame();
  target.end_frame(*frame);
  return true;
}

// What window_pattern.comp writes at (x, y).
inline void expected_pattern(std::uint32_t x, std::uint32_t y, std::uint32_t width,
                             std::uint32_t height, std::uint32_t frame, float out[4]) {
  out[0] = static_cast<float>(x) / static_cast<float>(width);
  out[1] = static_cast<float>(y) / static_cast<float>(height);
  out[2] = static_cast<float>((x + y + frame) % 7u) / 8.0f;
  out[3] = 1.0f;
}

}  // namespace lantern::runtime::test
