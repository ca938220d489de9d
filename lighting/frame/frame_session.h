// FrameSession: the one frame loop. A FrameRenderer's passes (scene.upload, gbuffer.*, the
// integrator's), the hooks between the HDR image and the output, the output pass and the
// target's delivery, recorded through one render graph and executor into any RenderTarget
// (headless or window), with GPU timestamps per pass. render, bench, capture, trade, play and
// the tests all drive it (through HeadlessSession without a window).
//
//   FrameSession session(device, target, renderer);
//   while (running) {
//     FrameTiming timing;
//     if (!session.render(world.step(), hooks, &timing)) continue;  // no frame from the target
//   }
// A window target keeps frames in flight: render() reports the timing of the last frame whose
// GPU results came back (for a headless target, the frame just rendered).
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "engine/world/frame_snapshot.h"
#include "runtime/graph/render_graph.h"
#include "runtime/runtime_fwd.h"
#include "runtime/target/render_target.h"

namespace lantern::lighting {

class FrameRenderer;

struct FrameTiming {
  // GPU ms of the frame's passes except the delivery passes (frame.output, target.*), which are
  // in `passes` but not in this sum.
  double gpu_ms = 0.0;
  double wall_ms = 0.0;          // host wall time of render(): update, record, submit (+ wait)
  double scene_update_ms = 0.0;  // CPU part of it spent updating the scene from the snapshot
  std::vector<std::pair<std::string, double>> passes;   // GPU ms per pass, in order
  std::vector<std::pair<std::string, double>> systems;  // CPU ms per world system (filled by
                                                        // the caller that steps the world)
  double step_ms = 0.0;                                 // host wall time of the world step
  bool gpu_valid = false;  // gpu_ms/passes hold a finished frame's timestamps
};

// Passes that deliver the image rather than render it (excluded from FrameTiming::gpu_ms).
bool is_delivery_pass(const std::string& name);

// Where a caller adds passes to a frame.
struct FrameHooks {
  // Between the HDR image and the output (accumulation; later denoise and upscale): gets the
  // integrator's HDR buffer, returns the one the output pass reads.
  std::function<runtime::graph::BufferHandle(runtime::graph::RenderGraph&,
                                             runtime::graph::BufferHandle)>
      hdr;
  // After the output pass, before delivery (the play UI): returns the image to deliver.
  std::function<runtime::graph::ImageHandle(runtime::graph::RenderGraph&,
                                            runtime::graph::ImageHandle,
                                            const runtime::TargetFrame&)>
      output;
  float exposure = 0.0f;  // the output pass's: 0 linear copy, > 0 exposure x filmic tonemap
};

class FrameSession {
 public:
  FrameSession(runtime::Device& device, runtime::RenderTarget& target, FrameRenderer& renderer);
  ~FrameSession();
  FrameSession(const FrameSession&) = delete;
  FrameSession& operator=(const FrameSession&) = delete;

  // Renders `snapshot` into the target's next frame. false: the target gave no frame (window
  // minimised or out of date); nothing was rendered. `timing` (optional) receives this call's
  // wall and scene-update times and the GPU times of the last finished frame.
  bool render(const FrameSnapshot& snapshot, const FrameHooks& hooks = {},
              FrameTiming* timing = nullptr);

  // The same in two steps, for a loop that must see the frame (its size) before it steps the
  // world: begin_frame() (nullopt: no frame now; `finished` gets the GPU times of the frame that
  // last used the slot, when a window keeps frames in flight), then render(frame, ...).
  std::optional<runtime::TargetFrame> begin_frame(FrameTiming* finished = nullptr);
  void render(const runtime::TargetFrame& frame, const FrameSnapshot& snapshot,
              const FrameHooks& hooks = {}, FrameTiming* timing = nullptr);

  // Renders with another FrameRenderer from the next frame on (play: integrator switch, shader
  // reload). A new renderer's first frame has no history (it invalidates the graph's).
  void set_renderer(FrameRenderer& renderer) { renderer_ = &renderer; }
  runtime::RenderTarget& target() { return target_; }
  FrameRenderer& renderer() { return *renderer_; }
  // The frame's graph, for hooks that add passes of their own (valid inside a hook).
  runtime::graph::RenderGraph& graph() { return graph_; }
  // GPU timestamps on one frame in `every` (1, the default: every frame; the other frames' timings
  // have gpu_valid false). On lavapipe a pass's timestamp pair costs ~60 us of wall time (the
  // end stamp flushes the context): 1.3 ms of a 3 ms frame at 16x9, ~1.7 of ~19 ms at 160x90.
  // play, which only shows them, times one frame in kPlayTimingInterval.
  void set_timing_interval(std::uint32_t every) { timing_interval_ = every > 0 ? every : 1; }

 private:
  runtime::RenderTarget& target_;
  FrameRenderer* renderer_;
  runtime::graph::RenderGraph graph_;
  std::unique_ptr<runtime::graph::GraphExecutor> executor_;
  std::vector<std::unique_ptr<runtime::GpuTimer>> timers_;  // one per frame slot
  std::vector<bool> timer_used_;  // the slot's last frame was timed
  std::uint32_t timing_interval_ = 1;
  std::uint64_t frames_ = 0;
};

}  // namespace lantern::lighting
