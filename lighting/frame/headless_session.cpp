// HeadlessSession: World + FrameRenderer + HeadlessTarget + FrameSession.
#include "lighting/frame/headless_session.h"

#include <fmt/format.h>

#include <chrono>
#include <cmath>

#include "engine/core/error.h"
#include "engine/world/world.h"
#include "lighting/denoise/denoise_settings.h"
#include "lighting/frame/frame_renderer.h"
#include "lighting/frame/hdr_readback.h"
#include "runtime/target/headless_target.h"

namespace lantern::lighting {
namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

}  // namespace

struct HeadlessSession::State {
  State(runtime::Device& device, runtime::ShaderLibrary& shaders,
        std::shared_ptr<const Level> level, const SessionOptions& o)
      : world(level, {.threads = o.world_threads,
                      .seed = o.world_seed.value_or(o.seed),
                      .fixed_dt = o.fixed_dt,
                      .aspect = static_cast<float>(o.width) / static_cast<float>(o.height)}),
        renderer(device, shaders, level, make_integrator(device, shaders, o.integrator), o.width,
                 o.height, o.seed),
        target(device, {.width = o.width, .height = o.height}),
        session(device, target, renderer),
        raw(device),
        gbuffer(device) {
    renderer.set_output(o.output);
    renderer.set_internal_size(
        static_cast<std::uint32_t>(std::lround(o.render_scale * static_cast<float>(o.width))),
        static_cast<std::uint32_t>(std::lround(o.render_scale * static_cast<float>(o.height))));
    renderer.set_denoise_settings(make_denoise_settings(o.integrator.preset, o.integrator.denoise));
    renderer.set_gbuffer_method(o.integrator.gbuffer);
  }

  World world;
  FrameRenderer renderer;
  runtime::HeadlessTarget target;
  FrameSession session;
  HdrReadback raw;
  GBufferReadback gbuffer;
};

HeadlessSession::HeadlessSession(runtime::Device& device, runtime::ShaderLibrary& shaders,
                                 std::shared_ptr<const Level> level,
                                 const SessionOptions& options)
    : options_(options) {
  if (options.width == 0 || options.height == 0) {
    throw InputError(
        fmt::format("render size {}x{} must be positive", options.width, options.height));
  }
  if (!(options.render_scale > 0.0f && options.render_scale <= 1.0f)) {
    throw InputError(fmt::format("render scale {} must be in (0, 1]", options.render_scale));
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

FrameTiming HeadlessSession::render(const FrameSnapshot& snapshot, runtime::ImageRGBA32F* image,
                                    runtime::ImageRGBA32F* raw, GBufferTexels* gbuffer) {
  State& s = *state_;
  FrameTiming timing;
  FrameHooks hooks;
  const bool raw_pass = raw != nullptr && s.renderer.output() != FrameOutput::Raw;
  if (raw_pass || gbuffer != nullptr) {
    hooks.hdr = [&s, raw_pass, gbuffer](runtime::graph::RenderGraph& graph,
                                        runtime::graph::BufferHandle hdr) {
      if (raw_pass) s.raw.add(graph, s.renderer.last_raw(), s.renderer.width(), s.renderer.height());
      if (gbuffer != nullptr) {
        s.gbuffer.add(graph, s.renderer.last_inputs().gbuffer, s.renderer.width(),
                      s.renderer.height());
      }
      return hdr;
    };
  }
  if (!s.session.render(snapshot, hooks, &timing)) {
    throw RuntimeError("the headless target gave no frame");
  }
  timing.step_ms = last_step_ms_;
  for (const SystemTiming& t : s.world.scheduler().timings()) {
    timing.systems.emplace_back(std::string(t.name), t.ms);
  }
  if (image) *image = s.target.read_output();
  if (raw != nullptr) *raw = raw_pass ? s.raw.read() : image ? *image : s.target.read_output();
  if (gbuffer != nullptr) *gbuffer = s.gbuffer.read();
  return timing;
}

World& HeadlessSession::world() { return state_->world; }
FrameRenderer& HeadlessSession::renderer() { return state_->renderer; }

}  // namespace lantern::lighting
