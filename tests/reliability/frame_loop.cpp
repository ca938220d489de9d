// FrameLoop: World + FrameRenderer + HeadlessTarget (see frame_loop.h).
#include "tests/reliability/frame_loop.h"

#include <malloc.h>
#include <unistd.h>

#include <fstream>

#include "engine/core/error.h"
#include "engine/world/world.h"
#include "lighting/frame/frame_renderer.h"
#include "runtime/core/device.h"
#include "runtime/graph/graph_executor.h"
#include "runtime/graph/render_graph.h"
#include "runtime/target/headless_target.h"

namespace lantern::reliability {

struct FrameLoop::State {
  State(runtime::Device& device, runtime::ShaderLibrary& shaders,
        std::shared_ptr<const Level> level, const LoopOptions& o)
      : world(level, {.threads = o.world_threads,
                      .seed = o.seed,
                      .fixed_dt = 1.0 / 60.0,
                      .aspect = static_cast<float>(o.width) / static_cast<float>(o.height)}),
        renderer(device, shaders, level, lighting::make_integrator(device, shaders, o.integrator),
                 o.width, o.height, o.seed),
        target(device, {.width = o.width, .height = o.height}),
        executor(device) {
    renderer.warm_up();
  }
  World world;
  lighting::FrameRenderer renderer;
  runtime::HeadlessTarget target;
  runtime::graph::RenderGraph graph;
  runtime::graph::GraphExecutor executor;
};

FrameLoop::FrameLoop(runtime::Device& device, runtime::ShaderLibrary& shaders,
                     std::shared_ptr<const Level> level, const LoopOptions& options)
    : state_(std::make_unique<State>(device, shaders, std::move(level), options)) {}

FrameLoop::~FrameLoop() = default;

runtime::ImageRGBA32F FrameLoop::frame() {
  State& s = *state_;
  s.world.step();
  const std::shared_ptr<const FrameSnapshot> snapshot = s.world.latest();
  const auto target_frame = s.target.begin_frame();
  if (!target_frame) throw RuntimeError("reliability: the headless target gave no frame");
  s.graph.begin_frame();
  const runtime::graph::BufferHandle hdr = s.renderer.add_frame(s.graph, *snapshot);
  const runtime::graph::ImageHandle output = s.renderer.add_output_pass(
      s.graph, hdr, s.target.import_output(s.graph, *target_frame), 0.0f);
  s.target.add_delivery(s.graph, *target_frame, output);
  s.graph.bake(s.executor.compile_options());
  s.executor.record(s.graph, target_frame->cmd, nullptr);
  s.graph.end_frame();
  s.target.end_frame(*target_frame);
  return s.target.read_output();
}

std::uint64_t resident_bytes() {
  std::ifstream statm("/proc/self/statm");
  std::uint64_t size = 0, resident = 0;
  statm >> size >> resident;
  return resident * static_cast<std::uint64_t>(::sysconf(_SC_PAGESIZE));
}

std::uint64_t heap_bytes() {
  const struct mallinfo2 info = ::mallinfo2();
  return static_cast<std::uint64_t>(info.uordblks) + static_cast<std::uint64_t>(info.hblkhd);
}

}  // namespace lantern::reliability
