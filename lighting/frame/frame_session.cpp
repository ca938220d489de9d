// FrameSession: FrameRenderer + hooks + output + delivery through one graph (frame_session.h).
#include "lighting/frame/frame_session.h"

#include <fmt/format.h>

#include <chrono>

#include "engine/core/error.h"
#include "lighting/frame/frame_renderer.h"
#include "lighting/scene/gpu_scene.h"
#include "runtime/gpu/gpu_timer.h"
#include "runtime/graph/graph_executor.h"

namespace lantern::lighting {
namespace {

using Clock = std::chrono::steady_clock;

// Timestamps of up to this many passes per frame (a frame has ~15 today).
constexpr std::uint32_t kTimerScopes = 256;

void read_gpu_times(const runtime::GpuTimer& timer, FrameTiming& timing) {
  timing.passes.clear();
  timing.gpu_ms = 0.0;
  for (const runtime::GpuTimer::Result& r : timer.resolve()) {
    if (r.depth != 0) continue;
    timing.passes.emplace_back(r.name, r.ms);
    if (!is_delivery_pass(r.name)) timing.gpu_ms += r.ms;
  }
  timing.gpu_valid = true;
}

}  // namespace

bool is_delivery_pass(const std::string& name) {
  return name == "frame.output" || name.rfind("target.", 0) == 0;
}

FrameSession::FrameSession(runtime::Device& device, runtime::RenderTarget& target,
                           FrameRenderer& renderer)
    : target_(target),
      renderer_(&renderer),
      executor_(std::make_unique<runtime::graph::GraphExecutor>(device)) {
  // The scene's staging ring and the host G-buffer's hit ring (GpuScene::kStagingSlots slots)
  // reuse a slot only once the frame that used it has finished.
  if (target.frames_in_flight() >= GpuScene::kStagingSlots) {
    throw RuntimeError(fmt::format("frame session: {} frames in flight, the scene's rings hold {}",
                                   target.frames_in_flight(), GpuScene::kStagingSlots - 1));
  }
  for (std::uint32_t i = 0; i < target.frames_in_flight(); ++i) {
    timers_.push_back(std::make_unique<runtime::GpuTimer>(device, kTimerScopes));
  }
  timer_used_.assign(timers_.size(), false);
}

FrameSession::~FrameSession() = default;

bool FrameSession::render(const FrameSnapshot& snapshot, const FrameHooks& hooks,
                          FrameTiming* timing) {
  const auto start = Clock::now();
  const std::optional<runtime::TargetFrame> frame = begin_frame(timing);
  if (!frame) return false;
  render(*frame, snapshot, hooks, timing);
  if (timing != nullptr) {
    timing->wall_ms = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
  }
  return true;
}

std::optional<runtime::TargetFrame> FrameSession::begin_frame(FrameTiming* finished) {
  std::optional<runtime::TargetFrame> frame = target_.begin_frame();
  if (!frame) return frame;
  // A window keeps frames in flight: the slot's previous frame has finished (begin_frame waited
  // for its fence), so its timestamps are ready now. A headless target's come in render().
  if (finished != nullptr && target_.frames_in_flight() > 1 && timer_used_.at(frame->slot)) {
    read_gpu_times(*timers_[frame->slot], *finished);
  }
  return frame;
}

void FrameSession::render(const runtime::TargetFrame& frame, const FrameSnapshot& snapshot,
                          const FrameHooks& hooks, FrameTiming* timing) {
  const auto start = Clock::now();
  const bool timed = frames_++ % timing_interval_ == 0;
  runtime::GpuTimer* timer = timed ? timers_.at(frame.slot).get() : nullptr;
  // On the host: a frame with host passes is submitted in parts before frame.cmd.
  if (timer != nullptr) timer->reset_on_host();
  timer_used_.at(frame.slot) = timed;
  graph_.begin_frame();
  runtime::graph::BufferHandle hdr = renderer_->add_frame(graph_, snapshot);
  if (hooks.hdr) hdr = hooks.hdr(graph_, hdr);
  runtime::graph::ImageHandle output = renderer_->add_output_pass(
      graph_, hdr, target_.import_output(graph_, frame), hooks.exposure);
  if (hooks.output) output = hooks.output(graph_, output, frame);
  target_.add_delivery(graph_, frame, output);
  graph_.bake(executor_->compile_options());
  executor_->record(graph_, frame.cmd, timer);
  graph_.end_frame();
  target_.end_frame(frame);

  if (timing != nullptr) {
    timing->scene_update_ms = renderer_->scene().last_update().cpu_ms;
    timing->wall_ms = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
    if (target_.frames_in_flight() == 1 && timer != nullptr) read_gpu_times(*timer, *timing);
  }
}

}  // namespace lantern::lighting
