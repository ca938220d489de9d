// Headless rendering of a running level: a World steps the level (moving objects, animated
// lights, camera paths) and a FrameRenderer renders its snapshots with the chosen integrator
// through the render graph into a HeadlessTarget, read back as linear radiance images (one per
// frame, or their mean), with GPU time per pass. What `lantern render` runs, and what the render
// tests call.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "engine/scene/level.h"
#include "lighting/frame/frame_renderer.h"
#include "lighting/integrators/integrator_registry.h"
#include "lighting/scene/gpu_scene.h"
#include "runtime/image/image.h"
#include "runtime/runtime_fwd.h"

namespace lantern::lighting {

struct OfflineRenderRequest {
  IntegratorConfig integrator;
  std::uint32_t width = 640;
  std::uint32_t height = 360;
  std::uint32_t frames = 1;
  // Steps the world this many frames without rendering first (`--frame K`); the first rendered
  // frame is then a camera cut (no history).
  std::uint32_t first_frame = 0;
  bool average = false;  // one image: the mean of the frames
  std::uint32_t seed = 1;
  // The world's seed when it differs from `seed` (SessionOptions::world_seed).
  std::optional<std::uint32_t> world_seed;
  // true: the world steps every rendered frame (objects, lights and camera move). false: every
  // frame renders the first rendered frame's snapshot (a static scene; only the random numbers
  // change), the accumulation a converged image needs.
  bool animate = true;
  // Raw integrator images or denoised ones (knobs: integrator.preset, integrator.denoise).
  FrameOutput output = FrameOutput::Raw;
  // Internal size / width x height (SessionOptions::render_scale): below 1 the images are
  // upscaled to width x height by upscale.temporal.
  float render_scale = 1.0f;
};

struct OfflineRenderResult {
  std::vector<runtime::ImageRGBA32F> images;  // one per frame, or one mean image
  // With `average` and at least 2 frames: the mean's standard error per pixel and channel
  // (runtime::ImageAccumulator::standard_error); empty otherwise.
  runtime::ImageRGBA32F standard_error;
  // GPU ms per frame: the sum of the renderer's passes (scene.upload, gbuffer*, the
  // integrator's); frame.output and target.readback are in pass_ms but not here.
  std::vector<double> frame_ms;
  std::vector<double> frame_wall_ms;  // CPU wall time per frame: update, record, submit, wait
  std::vector<std::vector<std::pair<std::string, double>>> pass_ms;  // per frame: pass -> ms
  std::vector<double> scene_update_ms;          // CPU cost of GpuScene::update per frame
  std::vector<SceneUpdateStats> scene_updates;  // what each frame's scene update did
  double median_frame_ms() const;
  // Median GPU ms of pass `name` over the frames (0 when it never ran).
  double median_pass_ms(const std::string& name) const;
};

// Renders `level`. Throws lantern::InputError for integrators not implemented yet, bad integrator
// settings and bad sizes.
OfflineRenderResult render_offline(runtime::Device& device, runtime::ShaderLibrary& shaders,
                                   std::shared_ptr<const Level> level,
                                   const OfflineRenderRequest& request);
OfflineRenderResult render_offline(runtime::Device& device, runtime::ShaderLibrary& shaders,
                                   const Level& level, const OfflineRenderRequest& request);

}  // namespace lantern::lighting
