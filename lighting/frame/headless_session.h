// HeadlessSession: a level running without a window — a World stepping it and the FrameSession
// (lighting/frame/frame_session.h) rendering its snapshots into a HeadlessTarget, one frame per
// call, with the frame's timings (GPU per pass, CPU per world system, wall time). What
// `lantern render`, `bench`, `capture`, `trade`, render_offline and the tests drive.
//
//   HeadlessSession session(device, shaders, level, {.integrator = config, .width = 320, ...});
//   session.warm_up();
//   for (...) { const FrameSnapshot& s = session.step_world(); FrameTiming t = session.render(s); }
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "engine/world/frame_snapshot.h"
#include "lighting/frame/frame_renderer.h"
#include "lighting/frame/frame_session.h"
#include "lighting/frame/gbuffer_readback.h"
#include "lighting/integrators/integrator_registry.h"
#include "runtime/image/image.h"
#include "runtime/runtime_fwd.h"

namespace lantern {
class World;
}

namespace lantern::lighting {

class FrameRenderer;

struct SessionOptions {
  IntegratorConfig integrator;
  std::uint32_t width = 640;
  std::uint32_t height = 360;
  std::uint32_t seed = 1;
  // The world's random numbers (flickering lights) when they differ from `seed`'s: a reference
  // rendered with samples of its own for the world another run shows.
  std::optional<std::uint32_t> world_seed;
  unsigned world_threads = 1;        // scheduler worker threads (results do not depend on it)
  double fixed_dt = 1.0 / 60.0;      // simulated seconds per frame
  // What render()'s `image` holds: the raw integrator image or the denoised one (denoiser knobs:
  // integrator.preset and integrator.denoise).
  FrameOutput output = FrameOutput::Raw;
  // Internal size = round(scale x width/height) (0 < scale <= 1): below 1 the frame is upscaled
  // to width x height by upscale.temporal; `raw` images stay at the internal size.
  float render_scale = 1.0f;
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
  // of options().output back into it, with `raw` the integrator's raw image of the same frame
  // (the same as `image` when the output is raw), and with `gbuffer` the frame's G-buffer (at
  // the internal size).
  FrameTiming render(const FrameSnapshot& snapshot, runtime::ImageRGBA32F* image = nullptr,
                     runtime::ImageRGBA32F* raw = nullptr, GBufferTexels* gbuffer = nullptr);

  World& world();
  FrameRenderer& renderer();
  const SessionOptions& options() const { return options_; }

 private:
  struct State;
  SessionOptions options_;
  std::unique_ptr<State> state_;
  double last_step_ms_ = 0.0;
};

}  // namespace lantern::lighting
