// ReSTIR settings: presets, parsing of KEY=VALUE with range checks, and the key list.
#include "lighting/restir/restir_settings.h"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <iterator>

#include "engine/core/error.h"
#include "shared/reservoir_pack.h"

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

constexpr RestirChoice kBiasCorrections[] = {
    {"none", gpu::kBiasCorrectionNone,
     "1/M weights: the fastest, but darkens contact shadows and edges where neighbours differ"},
    {"balance", gpu::kBiasCorrectionBalance,
     "unbiased, O(k^2) target evaluations: fine for a few neighbours when accuracy matters most"},
    {"pairwise", gpu::kBiasCorrectionPairwise,
     "unbiased, O(k) target evaluations: the default, and the cheaper unbiased one as "
     "neighbours grow"},
};

constexpr RestirChoice kDebugViews[] = {
    {"none", gpu::kRestirDebugNone, "radiance: the image itself"},
    {"w", gpu::kRestirDebugW,
     "the final sample's contribution weight W: find where fireflies and dark holes come from"},
    {"m", gpu::kRestirDebugM,
     "the final reservoir's M over the M cap: see where history is short (disocclusions, cuts)"},
    {"age", gpu::kRestirDebugAge,
     "frames since the final sample was drawn: spot stale samples lingering (lower m_cap)"},
    {"light", gpu::kRestirDebugLight,
     "which light each pixel selected (hashed colour): see how far reuse spreads a light"},
    {"disocclusion", gpu::kRestirDebugDisocclusion,
     "restir.temporal's outcome (red: no history, green: reprojected, yellow: a retry matched): "
     "tune depth_threshold and normal_threshold"},
    {"motion", gpu::kRestirDebugMotion,
     "the G-buffer's motion vectors: check reprojection when history smears"},
};
constexpr RestirChoice kTemporalPermutations[] = {
    {"off", kTemporalPermutationOff,
     "every pixel continues its own history: the least raw noise (bias studies, raw EXRs)"},
    {"on", kTemporalPermutationOn,
     "every pixel takes a neighbour's history, drawn anew each frame: noisier raw frames "
     "whose errors differ from frame to frame"},
    {"denoised", kTemporalPermutationDenoised,
     "on where the denoiser consumes the frame (play, PNG, video), off for raw output: the "
     "default"},
};
// Row i names constant i: every constant named once, and "next view" is the next row.
constexpr bool rows_follow_constants(std::span<const RestirChoice> choices) {
  for (std::size_t i = 0; i < choices.size(); ++i) {
    if (choices[i].value != i) return false;
  }
  return true;
}
static_assert(rows_follow_constants(kBiasCorrections));
static_assert(rows_follow_constants(kDebugViews));
static_assert(rows_follow_constants(kTemporalPermutations));
static_assert(std::size(kDebugViews) == gpu::kRestirDebugCount, "a debug view lacks a name");

std::uint32_t parse_choice(std::string_view key, std::string_view value,
                           std::span<const RestirChoice> choices, const char* what) {
  std::string names;
  for (const RestirChoice& c : choices) {
    if (value == c.name) return c.value;
    names += fmt::format("{}{}", names.empty() ? "" : ", ", c.name);
  }
  throw InputError(
      fmt::format("restir setting '{}': '{}' is not {} ({})", key, value, what, names));
}

std::string format_float(float f) { return fmt::format("{}", f); }

}  // namespace

std::span<const RestirChoice> restir_bias_corrections() { return kBiasCorrections; }
std::span<const RestirChoice> restir_debug_views() { return kDebugViews; }
std::span<const RestirChoice> restir_temporal_permutations() { return kTemporalPermutations; }

const char* choice_name(std::span<const RestirChoice> choices, std::uint32_t value) {
  for (const RestirChoice& c : choices) {
    if (c.value == value) return c.name;
  }
  return "?";
}

std::vector<std::string> restir_preset_names() { return {"fast", "balanced", "quality"}; }

RestirSettings restir_preset(std::string_view name) {
  RestirSettings s;  // the defaults are "balanced"
  if (name == "balanced") return s;
  if (name == "fast") {
    s.light_candidates = 4;
    s.local_candidates = 4;
    s.grid_candidates = 1;
    s.spatial_passes = 1;
    s.neighbours = 2;
    s.disocclusion_boost = 2;
    s.bias_correction = gpu::kBiasCorrectionNone;
    s.volume.candidates = 4;
    s.volume.neighbours = 2;
    return s;
  }
  if (name == "quality") {
    s.light_candidates = 16;
    s.local_candidates = 16;
    s.grid_candidates = 4;
    s.bsdf_candidates = 1;
    s.spatial_passes = 2;
    s.neighbours = 5;
    s.disocclusion_boost = 3;
    s.bias_correction = gpu::kBiasCorrectionBalance;
    s.volume.candidates = 16;
    s.volume.neighbours = 5;
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
  } else if (key == "bsdf_min_gloss") {
    s.bsdf_min_gloss = parse_float(key, value, 0.0f, 1.0f);
  } else if (key == "temporal") {
    s.temporal = parse_bool(key, value);
  } else if (key == "temporal_permutation") {
    s.temporal_permutation =
        parse_choice(key, value, kTemporalPermutations, "a temporal permutation mode");
  } else if (key == "m_cap" || key == "m_cap_factor") {
    s.m_cap_factor = parse_float(key, value, 1.0f, 1000.0f);
  } else if (key == "m_cap_moving") {
    s.m_cap_moving = parse_float(key, value, 0.01f, 1.0f);
  } else if (key == "reservoir_stride") {
    s.reservoir_stride = parse_uint(key, value, 1, gpu::kRestirMaxReservoirStride);
  } else if (key == "spatial_passes") {
    s.spatial_passes = parse_uint(key, value, 0, gpu::kRestirMaxSpatialPasses);
  } else if (key == "neighbours" || key == "neighbors") {
    s.neighbours = parse_uint(key, value, 0, gpu::kRestirMaxNeighbours);
  } else if (key == "temporal_neighbours" || key == "temporal_neighbors") {
    s.temporal_neighbours = parse_uint(key, value, 0, gpu::kRestirMaxNeighbours);
  } else if (key == "disocclusion_boost") {
    s.disocclusion_boost = parse_uint(key, value, 0, gpu::kRestirMaxNeighbours);
  } else if (key == "radius") {
    s.radius = parse_float(key, value, 1.0f, 256.0f);
  } else if (key == "bias_correction" || key == "bias") {
    s.bias_correction = parse_choice(key, value, kBiasCorrections, "a bias correction");
  } else if (key == "presample_tiles") {
    s.presample_tiles = parse_uint(key, value, 0, gpu::kRestirMaxPresampleTiles);
  } else if (key == "local_candidates") {
    s.local_candidates = parse_uint(key, value, 0, gpu::kRestirMaxLocalCandidates);
  } else if (key == "grid_candidates") {
    s.grid_candidates = parse_uint(key, value, 0, gpu::kRestirMaxLightCandidates);
  } else if (key == "local_min_lights") {
    // Up to the most lights a packed reservoir can index (local_candidates = 0 is the off switch).
    s.local_min_lights = parse_uint(key, value, 1, gpu::kPackedMaxLights - 1);
  } else if (key == "light_spread") {
    if (value == "auto") {
      s.light_spread = kLightSpreadAuto;
    } else {
      try {
        s.light_spread = parse_float(key, value, 0.0f, 1e9f);
      } catch (const InputError& e) {
        throw InputError(fmt::format("{} (or auto: the spread measured at load)", e.what()));
      }
    }
  } else if (key == "visibility_reuse") {
    s.visibility_reuse = parse_uint(key, value, 0, 64);
  } else if (key == "initial_visibility") {
    s.initial_visibility = parse_bool(key, value);
  } else if (key == "boiling_filter") {
    s.boiling_filter = parse_float(key, value, 0.0f, 1.0f);
  } else if (key == "depth_threshold") {
    s.depth_threshold = parse_float(key, value, 0.001f, 1.0f);
  } else if (key == "normal_threshold") {
    s.normal_threshold = parse_float(key, value, -1.0f, 1.0f);
  } else if (key == "debug_view") {
    s.debug_view = parse_choice(key, value, kDebugViews, "a debug view");
  } else if (key == "volume_candidates") {
    s.volume.candidates = parse_uint(key, value, 1, gpu::kVolumeRestirMaxCandidates);
  } else if (key == "volume_temporal") {
    s.volume.temporal = parse_bool(key, value);
  } else if (key == "volume_m_cap") {
    s.volume.m_cap_factor = parse_float(key, value, 0.0f, 1000.0f);
  } else if (key == "volume_neighbours") {
    s.volume.neighbours = parse_uint(key, value, 0, gpu::kVolumeRestirMaxNeighbours);
  } else if (key == "volume_radius") {
    s.volume.radius = parse_float(key, value, 1.0f, 256.0f);
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
  if (s.reservoir_stride > 1 && s.visibility_reuse > 0) {
    throw InputError(fmt::format(
        "restir settings: visibility_reuse {} needs reservoir_stride 1 (a verdict is one "
        "pixel's; reservoir_stride {} shares each reservoir among {} pixels)",
        s.visibility_reuse, s.reservoir_stride, s.reservoir_stride * s.reservoir_stride));
  }
  return s;
}

std::vector<std::pair<std::string, std::string>> describe(const RestirSettings& s) {
  auto flag = [](bool b) { return std::string(b ? "on" : "off"); };
  return {
      {"light_candidates", std::to_string(s.light_candidates)},
      {"bsdf_candidates", std::to_string(s.bsdf_candidates)},
      {"bsdf_min_gloss", format_float(s.bsdf_min_gloss)},
      {"temporal", flag(s.temporal)},
      {"temporal_permutation", choice_name(kTemporalPermutations, s.temporal_permutation)},
      {"m_cap", format_float(s.m_cap_factor)},
      {"m_cap_moving", format_float(s.m_cap_moving)},
      {"reservoir_stride", std::to_string(s.reservoir_stride)},
      {"spatial_passes", std::to_string(s.spatial_passes)},
      {"neighbours", std::to_string(s.neighbours)},
      {"disocclusion_boost", std::to_string(s.disocclusion_boost)},
      {"temporal_neighbours", std::to_string(s.temporal_neighbours)},
      {"radius", format_float(s.radius)},
      {"presample_tiles", std::to_string(s.presample_tiles)},
      {"local_candidates", std::to_string(s.local_candidates)},
      {"grid_candidates", std::to_string(s.grid_candidates)},
      {"local_min_lights", std::to_string(s.local_min_lights)},
      {"light_spread", s.light_spread < 0.0f ? std::string("auto") : format_float(s.light_spread)},
      {"visibility_reuse", std::to_string(s.visibility_reuse)},
      {"bias_correction", choice_name(kBiasCorrections, s.bias_correction)},
      {"initial_visibility", flag(s.initial_visibility)},
      {"boiling_filter", format_float(s.boiling_filter)},
      {"depth_threshold", format_float(s.depth_threshold)},
      {"normal_threshold", format_float(s.normal_threshold)},
      {"debug_view", choice_name(kDebugViews, s.debug_view)},
      {"volume_candidates", std::to_string(s.volume.candidates)},
      {"volume_temporal", flag(s.volume.temporal)},
      {"volume_m_cap", format_float(s.volume.m_cap_factor)},
      {"volume_neighbours", std::to_string(s.volume.neighbours)},
      {"volume_radius", format_float(s.volume.radius)},
  };
}

}  // namespace lantern::lighting
