// `lantern play`: the level running in a window (see play_session.cpp for the frame loop).
// run_play() is what cmd_play.cpp calls and what tests/play drives with scripted input.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "apps/lantern/play/dynamic_resolution.h"
#include "apps/lantern/play/play_input.h"
#include "engine/scene/level.h"
#include "lighting/integrators/integrator_registry.h"
#include "lighting/restir/restir_integrator.h"

namespace lantern::app {

struct PlayConfig {
  std::string level = "cornell_lights";  // name or path
  // The level already loaded from `level` (the command loads it to validate settings); null:
  // run_play loads it.
  std::shared_ptr<const Level> loaded_level;
  lighting::IntegratorConfig integrator{.name = lighting::RestirIntegrator::kName};
  // Initial window size (the output size follows the window); 0 x 0: by the device, 320x180 on
  // a CPU device (lavapipe), 1280x720 elsewhere.
  std::uint32_t width = 640;
  std::uint32_t height = 360;
  // The internal size moves between min_scale x window and the window to hold target_ms
  // (dynamic_resolution.h; target_ms 0: always the window size).
  DynamicResolutionConfig dynamic_resolution;
  std::uint32_t seed = 1;
  std::string device = "auto";
  std::uint64_t max_frames = 0;  // 0: until Esc / close / a script's quit
  InputScript script;
  bool show_panel = false;
  double watch_interval_s = 1.0;            // shader source polling; 0: every frame
  std::filesystem::path shader_source_dir;  // empty: ShaderReloader::default_source_dir()
  // Called before each rendered frame with its index (tests: edit shaders mid-run).
  std::function<void(std::uint64_t frame)> on_frame;
};

struct PlayReport {
  std::uint64_t frames = 0;         // frames rendered and presented
  std::uint64_t skipped = 0;        // polls without a frame (minimised, no swapchain image)
  double camera_travel = 0.0;       // metres the camera moved in total
  std::uint64_t manual_frames = 0;  // frames under manual camera control
  std::uint64_t camera_cuts = 0;    // snapshots with camera_cut (frame 0 included)
  std::uint64_t panel_frames = 0;   // frames with the panel drawn
  std::uint32_t max_ui_triangles = 0;
  std::uint32_t reloads_ok = 0;
  std::uint32_t reload_failures = 0;
  std::string last_reload_error;
  std::uint32_t spawned_lights = 0;
  bool flashlight = false;
  std::uint32_t rebuilds = 0;    // integrator rebuilds (switches, reloads)
  std::string integrator;        // at the end
  std::vector<std::pair<std::string, std::string>> integrator_settings;  // its settings at the end
  std::vector<double> frame_ms;  // GPU ms per frame (sum of the frame's passes)
  std::vector<double> wall_ms;   // host ms per frame
  std::uint64_t validation_errors = 0;
  // Internal (render) sizes seen over the frames, and how often dynamic resolution changed it.
  std::uint32_t min_internal_width = 0, min_internal_height = 0;
  std::uint32_t max_internal_width = 0, max_internal_height = 0;
  std::uint32_t output_width = 0, output_height = 0;  // the window's, at the end
  std::uint32_t resolution_changes = 0;
  std::vector<double> interval_ms;  // host ms between consecutive rendered frames
};

// Throws InputError for bad input (level, integrator settings), RuntimeError for failures,
// including validation errors at the end.
PlayReport run_play(const PlayConfig& config);

}  // namespace lantern::app
