// HeadlessSession: World + FrameRenderer + HeadlessTarget + graph executor + GPU timer.
#include "lighting/frame/headless_session.h"

#include <fmt/format.h>

#include <chrono>

#include "engine/core/error.h"
#include "engine/world/world.h"
#include "lighting/frame/frame_renderer.h"
#include "runtime/gpu/gpu_timer.h"
#include "runtime/graph/graph_executor.h"
#include "runtime/graph/render_graph.h"
#include "runtime/target/headless_target.h"

namespace lantern::lighting {
namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

}  // namespace

bool is_delivery_pass(const std::string& name) {
  return name == "frame.output" || name.rfind("target.", 0) == 0;
}

struct HeadlessSession::State {
  State(runtime::Device& device, runtime::ShaderLibrary& shaders,
        std::shared_ptr<const Level> level, const SessionOptions& o)
      : world(level, {.threads = o.world_threads,
                      .seed = o.seed,
                      .fixed_dt = o.fixed_dt,
                      .aspect = static_cast<float>(o.width) / static_cast<float>(o.height)}),
        renderer(device, shaders, level, make_integrator(device, shaders, o.integrator), o.width,
                 o.height, o.seed),
        target(device, {.width = o.width, .height = o.height}),
        executor(device),
        timer(device, 256) {}

  World world;
  FrameRenderer renderer;
  runtime::HeadlessTarget target;
  runtime::graph::RenderGraph graph;
  runtime::graph::GraphExecutor executor;
  runtime::GpuTimer timer;
};

HeadlessSession::HeadlessSession(runtime::Device& device, runtime::ShaderLibrary& shaders,
                                 std::shared_ptr<const Level> level,
                                 const SessionOptions& options)
    : options_(options) {
  if (options.width == 0 || options.height == 0) {
    throw InputError(
        fmt::format("render size {}x{} must be positive", options.width, options.height));
  }
  state_ = std::make_unique<State>(device, shaders, std::move(level), options);
}

HeadlessSession::~HeadlessSession() = default;

void HeadlessSession::warm_up() { state_->renderer.warm_up(); }

const FrameSnapshot& HeadlessSession::step_world() {
  const auto start = Clock::now();
  const FrameSnapshot& snapshot = state_->world.step();
  last_step_ms_ = ms_since(start);
  return snapshot;
}

void HeadlessSession::skip(std::uint32_t frames) {
  for (std::uint32_t k = 0; k < frames; ++k) state_->world.step();
  if (frames > 0) state_->world.request_camera_cut();
}

FrameTiming HeadlessSession::render(const FrameSnapshot& snapshot, runtime::ImageRGBA32F* image) {
  State& s = *state_;
  const auto start = Clock::now();
  const auto frame = s.target.begin_frame();
  if (!frame) throw RuntimeError("the headless target gave no frame");
  s.timer.reset(frame->cmd);
  s.graph.begin_frame();
  const runtime::graph::BufferHandle hdr = s.renderer.add_frame(s.graph, snapshot);
  FrameTiming timing;
  timing.scene_update_ms = s.renderer.scene().last_update().cpu_ms;
  const runtime::graph::ImageHandle output =
      s.renderer.add_output_pass(s.graph, hdr, s.target.import_output(s.graph, *frame), 0.0f);
  s.target.add_delivery(s.graph, *frame, output);
  s.graph.bake(s.executor.compile_options());
  s.executor.record(s.graph, frame->cmd, &s.timer);
  s.graph.end_frame();
  s.target.end_frame(*frame);
  timing.wall_ms = ms_since(start);
  timing.step_ms = last_step_ms_;

  for (const runtime::GpuTimer::Result& r : s.timer.resolve()) {
    if (r.depth != 0) continue;
    timing.passes.emplace_back(r.name, r.ms);
    if (!is_delivery_pass(r.name)) timing.gpu_ms += r.ms;
  }
  for (const SystemTiming& t : s.world.scheduler().timings()) {
    timing.systems.emplace_back(std::string(t.name), t.ms);
  }
  if (image) *image = s.target.read_output();
  return timing;
}

World& HeadlessSession::world() { return state_->world; }
FrameRenderer& HeadlessSession::renderer() { return state_->renderer; }

}  // namespace lantern::lighting
