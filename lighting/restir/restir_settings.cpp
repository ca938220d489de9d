// ReSTIR settings: presets, parsing of KEY=VALUE with range checks, and the key list.
#include "lighting/restir/restir_settings.h"

#include <fmt/format.h>

#include <charconv>
#include <cmath>

#include "engine/core/error.h"
#include "shared/restir.h"

namespace lantern::lighting {
namespace {

std::uint32_t parse_uint(std::string_view key, std::string_view value, std::uint32_t lo,
                         std::uint32_t hi) {
  std::uint64_t parsed = 0;
  const char* end = value.data() + value.size();
  auto [ptr, ec] = std::from_chars(value.data(), end, parsed);
  if (value.empty() || ec != std::errc{} || ptr != end) {
    throw InputError(fmt::format("restir setting '{}': '{}' is not a whole number", key, value));
  }
  if (parsed < lo || parsed > hi) {
    throw InputError(
        fmt::format("restir setting '{}': {} is outside {}..{}", key, value, lo, hi));
  }
  return static_cast<std::uint32_t>(parsed);
}

float parse_float(std::string_view key, std::string_view value, float lo, float hi) {
  // std::from_chars for floats is in GCC 12's libstdc++.
  float parsed = 0.0f;
  const char* end = value.data() + value.size();
  auto [ptr, ec] = std::from_chars(value.data(), end, parsed);
  if (value.empty() || ec != std::errc{} || ptr != end || !std::isfinite(parsed)) {
    throw InputError(fmt::format("restir setting '{}': '{}' is not a finite number", key, value));
  }
  if (parsed < lo || parsed > hi) {
    throw InputError(fmt::format("restir setting '{}': {} is outside {}..{}", key, value, lo, hi));
  }
  return parsed;
}

bool parse_bool(std::string_view key, std::string_view value) {
  if (value == "1" || value == "true" || value == "on" || value == "yes") return true;
  if (value == "0" || value == "false" || value == "off" || value == "no") return false;
  throw InputError(
      fmt::format("restir setting '{}': '{}' is not a boolean (on/off, true/false, 1/0)", key, value));
}

RestirBiasCorrection parse_bias(std::string_view key, std::string_view value) {
  for (auto mode : {RestirBiasCorrection::None, RestirBiasCorrection::Balance,
                    RestirBiasCorrection::Pairwise}) {
    if (value == bias_correction_name(mode)) return mode;
  }
  throw InputError(fmt::format(
      "restir setting '{}': '{}' is not a bias correction (none, balance or pairwise)", key, value));
}

RestirDebugView parse_debug_view(std::string_view key, std::string_view value) {
  for (std::uint32_t v = 0; v < gpu::kRestirDebugCount; ++v) {
    if (value == debug_view_name(static_cast<RestirDebugView>(v)))
      return static_cast<RestirDebugView>(v);
  }
  throw InputError(fmt::format(
      "restir setting '{}': '{}' is not a debug view (none, w, m, age, light, disocclusion, "
      "motion)",
      key, value));
}

std::string format_float(float f) { return fmt::format("{}", f); }

}  // namespace

const char* bias_correction_name(RestirBiasCorrection mode) {
  switch (mode) {
    case RestirBiasCorrection::None:
      return "none";
    case RestirBiasCorrection::Balance:
      return "balance";
    case RestirBiasCorrection::Pairwise:
      return "pairwise";
  }
  return "?";
}

const char* debug_view_name(RestirDebugView view) {
  switch (view) {
    case RestirDebugView::None:
      return "none";
    case RestirDebugView::W:
      return "w";
    case RestirDebugView::M:
      return "m";
    case RestirDebugView::Age:
      return "age";
    case RestirDebugView::Light:
      return "light";
    case RestirDebugView::Disocclusion:
      return "disocclusion";
    case RestirDebugView::Motion:
      return "motion";
  }
  return "?";
}

std::vector<std::string> restir_preset_names() { return {"fast", "balanced", "quality"}; }

RestirSettings restir_preset(std::string_view name) {
  RestirSettings s;  // the defaults are "balanced"
  if (name == "balanced") return s;
  if (name == "fast") {
    s.light_candidates = 4;
    s.spatial_passes = 1;
    s.neighbours = 2;
    s.disocclusion_boost = 2;
    s.bias_correction = RestirBiasCorrection::None;
    return s;
  }
  if (name == "quality") {
    s.light_candidates = 16;
    s.bsdf_candidates = 1;
    s.spatial_passes = 2;
    s.neighbours = 5;
    s.disocclusion_boost = 3;
    s.bias_correction = RestirBiasCorrection::Balance;
    return s;
  }
  throw InputError(
      fmt::format("unknown restir preset '{}' (expected fast, balanced or quality)", name));
}

void apply_setting(RestirSettings& s, std::string_view key, std::string_view value) {
  if (key == "light_candidates") {
    s.light_candidates = parse_uint(key, value, 1, gpu::kRestirMaxLightCandidates);
  } else if (key == "bsdf_candidates") {
    s.bsdf_candidates = parse_uint(key, value, 0, gpu::kRestirMaxBsdfCandidates);
  } else if (key == "temporal") {
    s.temporal = parse_bool(key, value);
  } else if (key == "m_cap" || key == "m_cap_factor") {
    s.m_cap_factor = parse_float(key, value, 1.0f, 1000.0f);
  } else if (key == "spatial_passes") {
    s.spatial_passes = parse_uint(key, value, 0, gpu::kRestirMaxSpatialPasses);
  } else if (key == "neighbours" || key == "neighbors") {
    s.neighbours = parse_uint(key, value, 0, gpu::kRestirMaxNeighbours);
  } else if (key == "disocclusion_boost") {
    s.disocclusion_boost = parse_uint(key, value, 0, gpu::kRestirMaxNeighbours);
  } else if (key == "radius") {
    s.radius = parse_float(key, value, 1.0f, 256.0f);
  } else if (key == "bias_correction" || key == "bias") {
    s.bias_correction = parse_bias(key, value);
  } else if (key == "initial_visibility") {
    s.initial_visibility = parse_bool(key, value);
  } else if (key == "boiling_filter") {
    s.boiling_filter = parse_float(key, value, 0.0f, 1.0f);
  } else if (key == "depth_threshold") {
    s.depth_threshold = parse_float(key, value, 0.001f, 1.0f);
  } else if (key == "normal_threshold") {
    s.normal_threshold = parse_float(key, value, -1.0f, 1.0f);
  } else if (key == "debug_view") {
    s.debug_view = parse_debug_view(key, value);
  } else {
    std::string keys;
    for (const auto& [k, v] : describe(RestirSettings{})) keys += (keys.empty() ? "" : ", ") + k;
    throw InputError(fmt::format("unknown restir setting '{}' (settings: {})", key, keys));
  }
}

RestirSettings make_restir_settings(
    std::string_view preset, const std::vector<std::pair<std::string, std::string>>& settings) {
  RestirSettings s = restir_preset(preset);
  for (const auto& [key, value] : settings) apply_setting(s, key, value);
  return s;
}

std::vector<std::pair<std::string, std::string>> describe(const RestirSettings& s) {
  auto flag = [](bool b) { return std::string(b ? "on" : "off"); };
  return {
      {"light_candidates", std::to_string(s.light_candidates)},
      {"bsdf_candidates", std::to_string(s.bsdf_candidates)},
      {"temporal", flag(s.temporal)},
      {"m_cap", format_float(s.m_cap_factor)},
      {"spatial_passes", std::to_string(s.spatial_passes)},
      {"neighbours", std::to_string(s.neighbours)},
      {"disocclusion_boost", std::to_string(s.disocclusion_boost)},
      {"radius", format_float(s.radius)},
      {"bias_correction", bias_correction_name(s.bias_correction)},
      {"initial_visibility", flag(s.initial_visibility)},
      {"boiling_filter", format_float(s.boiling_filter)},
      {"depth_threshold", format_float(s.depth_threshold)},
      {"normal_threshold", format_float(s.normal_threshold)},
      {"debug_view", debug_view_name(s.debug_view)},
  };
}

}  // namespace lantern::lighting
