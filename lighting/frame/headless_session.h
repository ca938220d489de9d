// HeadlessSession: a level running without a window — a World stepping it and a FrameRenderer
// rendering its snapshots through the render graph into a HeadlessTarget, one frame per call,
// with the frame's timings (GPU per pass, CPU per world system, wall time). What `lantern render`,
// `bench`, `capture` and `trade` drive.
//
//   HeadlessSession session(device, shaders, level, {.integrator = config, .width = 320, ...});
//   session.warm_up();
//   for (...) { const FrameSnapshot& s = session.step_world(); FrameTiming t = session.render(s); }
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "engine/world/frame_snapshot.h"
#include "lighting/integrators/integrator_registry.h"
#include "runtime/image/image.h"

namespace lantern {
class World;
}

namespace lantern::runtime {
class Device;
class ShaderLibrary;
}  // namespace lantern::runtime

namespace lantern::lighting {

class FrameRenderer;

struct SessionOptions {
  IntegratorConfig integrator;
  std::uint32_t width = 640;
  std::uint32_t height = 360;
  std::uint32_t seed = 1;
  unsigned world_threads = 1;        // scheduler worker threads (results do not depend on it)
  double fixed_dt = 1.0 / 60.0;      // simulated seconds per frame
};

struct FrameTiming {
  // GPU ms of the frame's rendering passes (scene.upload, gbuffer, the integrator's); the
  // delivery passes (frame.output, target.*) are in `passes` but not in this sum.
  double gpu_ms = 0.0;
  double wall_ms = 0.0;          // host wall time of render(): update, record, submit, wait
  double scene_update_ms = 0.0;  // CPU part of it spent updating the scene from the snapshot
  std::vector<std::pair<std::string, double>> passes;   // GPU ms per pass, in order
  std::vector<std::pair<std::string, double>> systems;  // CPU ms per world system (last step)
  double step_ms = 0.0;                                 // host wall time of the last step_world()
};

class HeadlessSession {
 public:
  // Loads nothing itself: `level` is already loaded. InputError on bad options or settings.
  HeadlessSession(runtime::Device& device, runtime::ShaderLibrary& shaders,
                  std::shared_ptr<const Level> level, const SessionOptions& options);
  ~HeadlessSession();
  HeadlessSession(const HeadlessSession&) = delete;
  HeadlessSession& operator=(const HeadlessSession&) = delete;

  void warm_up();
  // Simulates one frame; its snapshot is valid until the next step.
  const FrameSnapshot& step_world();
  // Steps `frames` frames without rendering, then requests a camera cut (`--frame K`).
  void skip(std::uint32_t frames);
  // Renders `snapshot` (usually the last step_world()'s); with `image`, reads the linear radiance
  // back into it.
  FrameTiming render(const FrameSnapshot& snapshot, runtime::ImageRGBA32F* image = nullptr);

  World& world();
  FrameRenderer& renderer();
  const SessionOptions& options() const { return options_; }

 private:
  struct State;
  SessionOptions options_;
  std::unique_ptr<State> state_;
  double last_step_ms_ = 0.0;
};

// Passes that deliver the image rather than render it (excluded from FrameTiming::gpu_ms).
bool is_delivery_pass(const std::string& name);

}  // namespace lantern::lighting
