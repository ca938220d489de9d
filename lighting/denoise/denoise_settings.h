// The denoiser's knobs (lighting/denoise/denoiser.h): every one settable by name
// (`--set denoise.KEY=VALUE`, a level's "denoise" settings, the play panel), grouped into the
// same presets as ReSTIR (fast, balanced, quality). One table row per key
// (denoise_settings.cpp: name, range, when to change it, where it lives); the GPU sees them
// through gpu::DenoisePush (shaders/shared/denoise.h).
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "shared/denoise.h"

namespace lantern::lighting {

struct DenoiseSettings {
  bool enabled = true;                // off: the player sees the raw image
  std::uint32_t atrous_iterations = 3;
  float color_alpha = 0.1f;
  float moments_alpha = 0.2f;
  float phi_luminance = 2.0f;
  float phi_normal = 64.0f;
  float phi_depth = 0.02f;
  float firefly = 4.0f;
  float neighbour_clamp = 2.0f;
  float antilag = 1.0f;
  float stabilize = 0.7f;       // weight of last frame's output in this frame's (0: off)
  float stabilize_band = 1.0f;  // how far that output may differ, in standard deviations
  float max_history = 32.0f;
  float repay = 0.25f;  // share of the light the clamps took given back each frame (0: dropped)
  bool confidence = true;  // weigh each frame by the integrator's confidence (ReSTIR's M)
};

// One key of DenoiseSettings: its `--set denoise.` name, range and when to change it (the
// panel's tooltip, the README's table).
struct DenoiseKey {
  const char* name;
  const char* when;
  float lo;
  float hi;
  bool integer;  // whole numbers only (bools are 0..1 integers written on/off)
};
std::span<const DenoiseKey> denoise_keys();

// `preset` (fast|balanced|quality) then `changes` (KEY=VALUE, keys without the "denoise."
// prefix), range-checked: InputError naming the key or value otherwise.
DenoiseSettings make_denoise_settings(
    std::string_view preset, const std::vector<std::pair<std::string, std::string>>& changes);
void apply_denoise_setting(DenoiseSettings& s, std::string_view key, std::string_view value);
// A key's value as a number (bools 0/1), and setting one clamped to its range (the panel's
// sliders); InputError for an unknown key.
float denoise_value(const DenoiseSettings& s, std::string_view key);
void set_denoise_value(DenoiseSettings& s, std::string_view key, float value);
// Every key with its value, in denoise_keys() order.
std::vector<std::pair<std::string, std::string>> describe_denoise_settings(const DenoiseSettings& s);

}  // namespace lantern::lighting
