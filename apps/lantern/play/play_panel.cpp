// The F1 panel (play_panel.h).
#include "apps/lantern/play/play_panel.h"

#include <fmt/format.h>
#include <imgui.h>

#include <algorithm>
#include <span>
#include <vector>

#include "lighting/restir/restir_integrator.h"

namespace lantern::app {
namespace {

using lighting::IntegratorEntry;
using lighting::RestirChoice;

std::string fmt_value(float value, const char* unit) {
  return fmt::format("{:.2f} {}", value, unit);
}

void plot(const char* label, const std::deque<float>& series, const char* unit) {
  if (series.empty()) return;
  const std::vector<float> values(series.begin(), series.end());
  const float top = *std::max_element(values.begin(), values.end());
  const std::string overlay = fmt_value(values.back(), unit);
  ImGui::PlotLines(label, values.data(), static_cast<int>(values.size()), 0, overlay.c_str(), 0.0f,
                   top * 1.1f + 1e-3f, ImVec2(0.0f, 36.0f));
}

}  // namespace

void push_sample(std::deque<float>& series, float value) {
  series.push_back(value);
  while (series.size() > kGraphFrames) series.pop_front();
}

std::string play_keys_help() {
  std::string keys, names;
  const std::span<const IntegratorEntry> list = lighting::integrators();
  for (std::size_t i = 0; i < list.size() && i < kIntegratorKeys; ++i) {
    keys += fmt::format("{}{}", i == 0 ? "" : "/", i + 1);
    names += fmt::format("{}{}", i == 0 ? "" : "/", list[i].name);
  }
  return fmt::format(
      "Right mouse + move: look   WASD: fly   Q/E: down/up   Shift: faster   wheel: speed\n"
      "P: back on the camera path   F: flashlight   L: level lights   K: emissive surfaces\n"
      "Space: spawn a light where you look   C: clear spawned lights\n"
      "{}: {}   V: next debug view   F1: panel   Esc: quit",
      keys, names);
}

void draw_panel(PanelState& s) {
  ImGui::SetNextWindowPos(ImVec2(8.0f, 8.0f), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(ImVec2(360.0f, 0.0f), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowBgAlpha(0.85f);
  if (!ImGui::Begin("lantern play (F1)")) {
    ImGui::End();
    return;
  }
  ImGui::Text("%s  %ux%u", s.level.c_str(), s.width, s.height);
  if (s.target_ms > 0.0) {
    ImGui::Text("internal %ux%u (%.0f%%), target %.1f ms", s.internal_width, s.internal_height,
                s.width > 0 ? 100.0 * s.internal_width / s.width : 0.0, s.target_ms);
  } else {
    ImGui::Text("internal %ux%u (dynamic resolution off)", s.internal_width, s.internal_height);
  }
  if (!s.frame_ms.empty()) {
    ImGui::Text("frame %.2f ms GPU, %.1f ms wall (%.1f fps)", s.frame_ms.back(),
                s.wall_ms.empty() ? 0.0f : s.wall_ms.back(),
                s.wall_ms.empty() || s.wall_ms.back() <= 0.0f ? 0.0f : 1000.0f / s.wall_ms.back());
    plot("GPU ms", s.frame_ms, "ms");
    plot("wall ms", s.wall_ms, "ms");
  }

  if (ImGui::CollapsingHeader("Integrator", ImGuiTreeNodeFlags_DefaultOpen)) {
    if (ImGui::BeginCombo("integrator", s.integrator.c_str())) {
      for (const IntegratorEntry& entry : lighting::integrators()) {
        const bool current = s.integrator == entry.name;
        if (ImGui::Selectable(entry.name, current) && !current) {
          s.integrator = entry.name;
          s.rebuild = true;
        }
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", entry.description);
      }
      ImGui::EndCombo();
    }
    if (lighting::find_integrator(s.integrator).progressive) {
      ImGui::Checkbox("accumulate while still", &s.progressive);
      ImGui::SameLine();
      ImGui::Text("%u frames", s.accumulated);
    }
  }

  if (s.integrator == lighting::RestirIntegrator::kName &&
      ImGui::CollapsingHeader("ReSTIR", ImGuiTreeNodeFlags_DefaultOpen)) {
    const std::vector<std::string> presets = lighting::restir_preset_names();
    int preset = 0;
    for (std::size_t i = 0; i < presets.size(); ++i)
      if (presets[i] == s.preset) preset = static_cast<int>(i);
    if (ImGui::BeginCombo("preset", s.preset.c_str())) {
      for (std::size_t i = 0; i < presets.size(); ++i) {
        if (ImGui::Selectable(presets[i].c_str(), static_cast<int>(i) == preset)) {
          s.preset = presets[i];
          s.restir = lighting::restir_preset(s.preset);
          s.settings_changed = true;
        }
      }
      ImGui::EndCombo();
    }
    lighting::RestirSettings& r = s.restir;
    bool c = false;
    auto slider_u = [&](const char* label, std::uint32_t& v, int lo, int hi) {
      int x = static_cast<int>(v);
      if (ImGui::SliderInt(label, &x, lo, hi)) {
        v = static_cast<std::uint32_t>(std::clamp(x, lo, hi));
        c = true;
      }
    };
    auto slider_f = [&](const char* label, float& v, float lo, float hi, const char* fmt) {
      if (ImGui::SliderFloat(label, &v, lo, hi, fmt)) {
        v = std::clamp(v, lo, hi);
        c = true;
      }
    };
    // A combo over a table of named shared constants, each row's sentence as its tooltip.
    auto choice = [&](const char* label, std::uint32_t& v, std::span<const RestirChoice> rows) {
      if (!ImGui::BeginCombo(label, lighting::choice_name(rows, v))) return;
      for (const RestirChoice& row : rows) {
        if (ImGui::Selectable(row.name, row.value == v) && row.value != v) {
          v = row.value;
          c = true;
        }
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", row.when);
      }
      ImGui::EndCombo();
    };
    constexpr int kMaxNeighbours = static_cast<int>(gpu::kRestirMaxNeighbours);
    slider_u("light candidates", r.light_candidates, 1, 64);
    slider_u("BSDF candidates", r.bsdf_candidates, 0, 8);
    slider_f("BSDF min gloss", r.bsdf_min_gloss, 0.0f, 1.0f, "%.2f");
    slider_u("local candidates", r.local_candidates, 0,
             static_cast<int>(gpu::kRestirMaxLocalCandidates));
    slider_u("grid candidates", r.grid_candidates, 0, 16);
    slider_u("presample tiles", r.presample_tiles, 0,
             static_cast<int>(gpu::kRestirMaxPresampleTiles));
    slider_u("visibility reuse", r.visibility_reuse, 0, 64);
    c |= ImGui::Checkbox("temporal reuse", &r.temporal);
    slider_f("M cap factor", r.m_cap_factor, 1.0f, 100.0f, "%.1f");
    slider_f("M cap where moving", r.m_cap_moving, 0.01f, 1.0f, "%.2f");
    slider_u("temporal neighbours", r.temporal_neighbours, 0, kMaxNeighbours);
    slider_u("reservoir stride", r.reservoir_stride, 1,
             static_cast<int>(gpu::kRestirMaxReservoirStride));
    slider_u("spatial passes", r.spatial_passes, 0, static_cast<int>(gpu::kRestirMaxSpatialPasses));
    slider_u("neighbours", r.neighbours, 0, kMaxNeighbours);
    slider_u("disocclusion boost", r.disocclusion_boost, 0, kMaxNeighbours);
    slider_f("radius (px)", r.radius, 1.0f, 64.0f, "%.1f");
    choice("bias correction", r.bias_correction, lighting::restir_bias_corrections());
    choice("temporal permutation", r.temporal_permutation,
           lighting::restir_temporal_permutations());
    c |= ImGui::Checkbox("initial visibility", &r.initial_visibility);
    slider_f("boiling filter", r.boiling_filter, 0.0f, 1.0f, "%.2f");
    slider_f("depth threshold", r.depth_threshold, 0.001f, 1.0f, "%.3f");
    slider_f("normal threshold", r.normal_threshold, -1.0f, 1.0f, "%.2f");
    choice("debug view", r.debug_view, lighting::restir_debug_views());
    // The media reservoirs (levels with volumes; no effect elsewhere).
    ImGui::Separator();
    ImGui::TextUnformatted("media (volumes)");
    slider_u("volume candidates", r.volume.candidates, 1,
             static_cast<int>(gpu::kVolumeRestirMaxCandidates));
    c |= ImGui::Checkbox("volume temporal", &r.volume.temporal);
    slider_f("volume M cap factor", r.volume.m_cap_factor, 0.0f, 100.0f, "%.1f");
    slider_u("volume neighbours", r.volume.neighbours, 0,
             static_cast<int>(gpu::kVolumeRestirMaxNeighbours));
    slider_f("volume radius (px)", r.volume.radius, 1.0f, 64.0f, "%.1f");
    if (c) s.settings_changed = true;
  }

  if (ImGui::CollapsingHeader("Denoiser", ImGuiTreeNodeFlags_DefaultOpen)) {
    // One widget per row of the denoiser's key table, its sentence as the tooltip.
    for (const lighting::DenoiseKey& key : lighting::denoise_keys()) {
      float v = lighting::denoise_value(s.denoise, key.name);
      bool changed = false;
      if (key.integer && key.hi == 1.0f) {
        bool on = v != 0.0f;
        changed = ImGui::Checkbox(key.name, &on);
        v = on ? 1.0f : 0.0f;
      } else if (key.integer) {
        int x = static_cast<int>(v);
        changed = ImGui::SliderInt(key.name, &x, static_cast<int>(key.lo), static_cast<int>(key.hi));
        v = static_cast<float>(x);
      } else {
        changed = ImGui::SliderFloat(key.name, &v, key.lo, key.hi, "%.3g",
                                     key.hi / std::max(key.lo, 1e-3f) > 100.0f
                                         ? ImGuiSliderFlags_Logarithmic
                                         : ImGuiSliderFlags_None);
      }
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", key.when);
      if (changed) lighting::set_denoise_value(s.denoise, key.name, v);
    }
  }

  if (ImGui::CollapsingHeader("GPU passes", ImGuiTreeNodeFlags_DefaultOpen)) {
    for (const auto& [name, series] : s.pass_ms) plot(name.c_str(), series, "ms");
  }

  if (ImGui::CollapsingHeader("Lights and camera", ImGuiTreeNodeFlags_DefaultOpen)) {
    if (ImGui::Checkbox("flashlight (F)", &s.flashlight)) s.toggle_flashlight = true;
    ImGui::SameLine();
    if (ImGui::Checkbox("level lights (L)", &s.level_lights)) s.toggle_level_lights = true;
    if (ImGui::Checkbox("emissive surfaces (K)", &s.emissive)) s.toggle_emissive = true;
    if (ImGui::Button("spawn light (Space)")) s.spawn_light = true;
    ImGui::SameLine();
    if (ImGui::Button("clear (C)")) s.clear_lights = true;
    ImGui::SameLine();
    ImGui::Text("%u spawned", s.spawned);
    ImGui::Text("camera: %s, %.2f m/s", s.manual_camera ? "manual" : "path", s.camera_speed);
    ImGui::Text("at (%.2f, %.2f, %.2f)", s.camera_position[0], s.camera_position[1],
                s.camera_position[2]);
    if (s.manual_camera && ImGui::Button("back on path (P)")) s.resume_path = true;
  }

  if (ImGui::CollapsingHeader("Shaders", ImGuiTreeNodeFlags_DefaultOpen)) {
    ImGui::TextWrapped("hot reload: %s", s.reload_status.c_str());
    if (!s.reload_error.empty()) {
      ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.4f, 0.4f, 1.0f));
      ImGui::TextWrapped("%s", s.reload_error.c_str());
      ImGui::PopStyleColor();
    }
  }
  if (ImGui::CollapsingHeader("Keys")) ImGui::TextUnformatted(play_keys_help().c_str());
  ImGui::End();
}

}  // namespace lantern::app
