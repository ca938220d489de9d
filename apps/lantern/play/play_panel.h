// The F1 panel of `lantern play` (ImGui widgets; drawn by PlayUi): integrator switch, ReSTIR
// preset and every knob, debug views, progressive accumulation, per-pass GPU times as live graphs,
// frame time, lights, camera, shader reload status and the key list. It edits a PanelState; the
// session applies what changed.
#pragma once

#include <cstdint>
#include <deque>
#include <map>
#include <string>

#include "lighting/denoise/denoise_settings.h"
#include "lighting/integrators/integrator_registry.h"
#include "lighting/restir/restir_settings.h"

namespace lantern::app {

inline constexpr std::size_t kGraphFrames = 120;
inline constexpr std::size_t kIntegratorKeys = 9;  // keys 1..9: the registry's first nine

struct PanelState {
  // Edited by the panel.
  std::string integrator;  // a registry name (lighting/integrators/integrator_registry.h)
  std::string preset = "balanced";
  lighting::RestirSettings restir;
  bool progressive = true;  // accumulate while still (integrators whose entry is progressive)
  lighting::DenoiseSettings denoise;  // the frame's denoiser: applied every frame
  // Requests (set by the panel, cleared by the session).
  bool rebuild = false;           // integrator or preset changed: new integrator
  bool settings_changed = false;  // a ReSTIR knob changed: Integrator::apply_settings
  bool toggle_flashlight = false, toggle_level_lights = false, toggle_emissive = false;
  bool spawn_light = false, clear_lights = false, resume_path = false;
  // Shown by the panel.
  std::string level;
  std::deque<float> frame_ms;                        // GPU, last kGraphFrames frames
  std::deque<float> wall_ms;                         // host, per frame
  std::map<std::string, std::deque<float>> pass_ms;  // GPU per pass
  std::uint32_t accumulated = 0;
  bool flashlight = false, level_lights = true, emissive = true;
  std::uint32_t spawned = 0;
  bool manual_camera = false;
  float camera_speed = 0.0f;
  float camera_position[3] = {0.0f, 0.0f, 0.0f};
  std::uint32_t width = 0, height = 0;                    // the window's (output) size
  std::uint32_t internal_width = 0, internal_height = 0;  // the render size (dynamic resolution)
  double target_ms = 0.0;                                 // its frame-time target (0: off)
  std::string reload_status = "watching";
  std::string reload_error;  // last failed reload's messages
};

// Appends `value`, keeping the last kGraphFrames.
void push_sample(std::deque<float>& series, float value);

// Draws the panel (between ImGui::NewFrame and Render).
void draw_panel(PanelState& state);

// The key list (panel, log, README); the number keys 1..9 pick the registry's integrators in order.
std::string play_keys_help();

}  // namespace lantern::app
