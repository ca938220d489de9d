// Denoiser settings: presets, KEY=VALUE parsing with range checks (denoise_settings.h).
#include "lighting/denoise/denoise_settings.h"

#include <fmt/format.h>

#include <charconv>
#include <cmath>

#include "engine/core/error.h"

namespace lantern::lighting {
namespace {

// One row per key: the table the parser, describe() and the panel read. `field` reaches the
// value (as float; integers and bools are stored through it).
struct Row {
  DenoiseKey key;
  float (*get)(const DenoiseSettings&);
  void (*set)(DenoiseSettings&, float);
  float fast, balanced, quality;
};

#define DENOISE_FIELD(member) \
  [](const DenoiseSettings& s) { return static_cast<float>(s.member); }, \
      [](DenoiseSettings& s, float v) { s.member = static_cast<decltype(s.member)>(v); }

const Row kRows[] = {
    {{"enabled", "off to see the raw ReSTIR image (what trade's raw error and EXR output measure)",
      0, 1, true},
     DENOISE_FIELD(enabled), 1, 1, 1},
    {{"atrous", "à-trous iterations (3x3 taps 2^i px apart): more smooths wider noise, blurs "
                "more detail; 0 keeps only temporal accumulation",
      0, gpu::kDenoiseMaxAtrousIterations, true},
     DENOISE_FIELD(atrous_iterations), 3, 3, 5},
    {{"color_alpha", "temporal blend floor: lower for smoother still images, higher when lights "
                     "change fast and the image lags",
      0.01f, 1, false},
     DENOISE_FIELD(color_alpha), 0.15f, 0.1f, 0.05f},
    {{"moments_alpha", "temporal blend floor of the variance estimate: lower steadies the "
                       "filter's strength over time",
      0.01f, 1, false},
     DENOISE_FIELD(moments_alpha), 0.2f, 0.2f, 0.2f},
    {{"phi_luminance", "luminance edge stop in standard deviations: higher blurs across "
                       "shadow edges, lower leaves more noise",
      0.1f, 100, false},
     DENOISE_FIELD(phi_luminance), 2, 2, 2},
    {{"phi_normal", "normal edge stop exponent: lower blurs across creases", 1, 1024, false},
     DENOISE_FIELD(phi_normal), 64, 64, 64},
    {{"phi_depth", "depth-plane edge stop (relative to the distance from the camera): raise if "
                   "grazing surfaces stay noisy, lower if objects bleed into each other",
      0.001f, 1, false},
     DENOISE_FIELD(phi_depth), 0.02f, 0.02f, 0.02f},
    {{"firefly", "clamp a new sample to mean + k sigma of its history (0 off): lower removes "
                 "more fireflies, and some energy",
      0, 100, false},
     DENOISE_FIELD(firefly), 4, 4, 4},
    {{"neighbour_clamp", "where a pixel has no history to judge a new sample by (new, "
                         "disoccluded, short or all black), clamp the sample to k x the second "
                         "brightest of its 8 neighbours on its surface (0 off): lower removes "
                         "more lone fireflies, and some energy",
      0, 100, false},
     DENOISE_FIELD(neighbour_clamp), 2, 2, 2},
    {{"repay", "give back this share of the light the firefly and neighbour clamps took from a "
               "pixel each frame, never above the clamp's limit (a black sample the history "
               "cannot judge has none; 0 off: dropped): higher keeps more of the image's energy, "
               "and leaves more noise",
      0, 1, false},
     DENOISE_FIELD(repay), 0.25f, 0.25f, 0.25f},
    {{"antilag", "hold the long colour history within k standard errors of the short luminance "
                 "history (0 off): lower follows changing light sooner, and adds some of the "
                 "short history's noise to a still view",
      0, 100, false},
     DENOISE_FIELD(antilag), 1, 1, 1},
    {{"stabilize", "blend this weight of last frame's output into this frame's, held near this "
                   "frame's (0 off): higher steadies a still view's residual noise, and lags "
                   "changing light by up to stabilize_band",
      0, 0.95f, false},
     DENOISE_FIELD(stabilize), 0.7f, 0.7f, 0.7f},
    {{"stabilize_band", "how far last frame's output may stay from this frame's, in the filtered "
                        "image's standard deviations: higher steadies more, and lags more",
      0, 100, false},
     DENOISE_FIELD(stabilize_band), 1, 1, 1},
    {{"max_history", "history length cap in frames (with confidence on, frames of the history's "
                     "mean confidence): lower when stale light lingers", 1, 256,
      false},
     DENOISE_FIELD(max_history), 32, 32, 32},
    {{"confidence", "weigh each frame in the temporal accumulation by the integrator's "
                    "confidence (ReSTIR's M: its warm-up frames count little); off: every frame "
                    "the same",
      0, 1, true},
     DENOISE_FIELD(confidence), 1, 1, 1},
};
#undef DENOISE_FIELD

const Row& find_row(std::string_view key) {
  for (const Row& r : kRows) {
    if (key == r.key.name) return r;
  }
  std::string names;
  for (const Row& r : kRows) names += fmt::format("{}{}", names.empty() ? "" : ", ", r.key.name);
  throw InputError(fmt::format("unknown denoise setting '{}' (keys: {})", key, names));
}

float parse_value(const Row& row, std::string_view value) {
  if (row.key.integer && row.key.hi == 1) {  // a bool
    if (value == "1" || value == "true" || value == "on" || value == "yes") return 1;
    if (value == "0" || value == "false" || value == "off" || value == "no") return 0;
    throw InputError(fmt::format(
        "denoise setting '{}': '{}' is not a boolean (on/off, true/false, 1/0)", row.key.name,
        value));
  }
  float parsed = 0.0f;
  const char* end = value.data() + value.size();
  auto [ptr, ec] = std::from_chars(value.data(), end, parsed);
  if (value.empty() || ec != std::errc{} || ptr != end || !std::isfinite(parsed) ||
      (row.key.integer && parsed != std::floor(parsed))) {
    throw InputError(fmt::format("denoise setting '{}': '{}' is not a {}", row.key.name, value,
                                 row.key.integer ? "whole number" : "finite number"));
  }
  if (parsed < row.key.lo || parsed > row.key.hi) {
    throw InputError(fmt::format("denoise setting '{}': {} is outside {}..{}", row.key.name,
                                 value, row.key.lo, row.key.hi));
  }
  return parsed;
}

}  // namespace

std::span<const DenoiseKey> denoise_keys() {
  static const std::vector<DenoiseKey> keys = [] {
    std::vector<DenoiseKey> k;
    for (const Row& r : kRows) k.push_back(r.key);
    return k;
  }();
  return keys;
}

void apply_denoise_setting(DenoiseSettings& s, std::string_view key, std::string_view value) {
  const Row& row = find_row(key);
  row.set(s, parse_value(row, value));
}

float denoise_value(const DenoiseSettings& s, std::string_view key) { return find_row(key).get(s); }

void set_denoise_value(DenoiseSettings& s, std::string_view key, float value) {
  const Row& row = find_row(key);
  value = std::fmin(std::fmax(value, row.key.lo), row.key.hi);
  row.set(s, row.key.integer ? std::round(value) : value);
}

DenoiseSettings make_denoise_settings(
    std::string_view preset, const std::vector<std::pair<std::string, std::string>>& changes) {
  DenoiseSettings s;
  if (preset != "fast" && preset != "balanced" && preset != "quality") {
    throw InputError(fmt::format("unknown preset '{}' (fast, balanced, quality)", preset));
  }
  for (const Row& r : kRows) {
    r.set(s, preset == "fast" ? r.fast : preset == "quality" ? r.quality : r.balanced);
  }
  for (const auto& [key, value] : changes) apply_denoise_setting(s, key, value);
  return s;
}

std::vector<std::pair<std::string, std::string>> describe_denoise_settings(
    const DenoiseSettings& s) {
  std::vector<std::pair<std::string, std::string>> out;
  for (const Row& r : kRows) {
    const float v = r.get(s);
    std::string text = r.key.integer && r.key.hi == 1 ? (v != 0 ? "on" : "off")
                       : r.key.integer                ? fmt::format("{}", static_cast<int>(v))
                                                      : fmt::format("{:g}", v);
    out.emplace_back(r.key.name, std::move(text));
  }
  return out;
}

}  // namespace lantern::lighting
