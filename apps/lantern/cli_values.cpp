// Parsing of flag values shared by several commands.
#include <fmt/format.h>

#include <charconv>
#include <optional>
#include <string>

#include "apps/lantern/commands.h"
#include "engine/core/error.h"
#include "engine/core/log.h"
#include "lighting/denoise/denoise_settings.h"
#include "lighting/scene/scene_data.h"
#include "lighting/visibility/host_visibility.h"
#include "runtime/core/device.h"

namespace lantern::app {
namespace {

std::uint32_t parse_dimension(std::string_view text, std::string_view size) {
  std::uint32_t value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size() || value == 0 || value > 16384)
    throw InputError(fmt::format("--size {}: expected WxH with W and H in 1..16384", size));
  return value;
}

// Strips "<integrator>." from a key; nullopt when the key names another integrator.
std::optional<std::string> key_for(const std::string& key, const std::string& integrator) {
  const std::string prefix = integrator + ".";
  if (key.rfind(prefix, 0) == 0) return key.substr(prefix.size());
  for (const lighting::IntegratorEntry& other : lighting::integrators()) {
    if (key.rfind(std::string(other.name) + ".", 0) == 0) return std::nullopt;
  }
  return key;
}

}  // namespace

lighting::IntegratorConfig integrator_config(const std::string& integrator,
                                             const CommonOptions& common, const Level& level) {
  lighting::IntegratorConfig config;
  config.name = lighting::find_integrator(integrator).name;
  config.preset = common.preset;
  const std::string& name = config.name;
  const std::string denoise = "denoise.";
  for (const auto& [key, value] : level.settings) {
    const std::string prefix = name + ".";
    if (key.rfind(prefix, 0) == 0) config.settings.emplace_back(key.substr(prefix.size()), value);
    if (key.rfind(denoise, 0) == 0) config.denoise.emplace_back(key.substr(denoise.size()), value);
  }
  for (const std::string& s : common.settings) {
    const std::size_t eq = s.find('=');
    if (eq == std::string::npos || eq == 0) {
      throw InputError(fmt::format("--set {}: expected KEY=VALUE", s));
    }
    if (s.substr(0, eq) == "visibility") continue;  // the frame's: visibility_setting()
    if (s.substr(0, eq) == "gbuffer") continue;  // the frame's: gbuffer_setting()
    if (s.rfind(denoise, 0) == 0) {  // the frame's denoiser, whichever integrator
      config.denoise.emplace_back(s.substr(denoise.size(), eq - denoise.size()), s.substr(eq + 1));
      continue;
    }
    const std::optional<std::string> key = key_for(s.substr(0, eq), name);
    if (!key) {
      log::warn("--set {}: not a {} setting, ignored", s, name);
      continue;
    }
    config.settings.emplace_back(*key, s.substr(eq + 1));
  }
  lighting::validate_integrator_config(config);
  (void)lighting::make_denoise_settings(config.preset, config.denoise);  // InputError on a bad key
  config.visibility = visibility_setting(common);
  config.gbuffer = gbuffer_setting(common);
  if (config.gbuffer == lighting::GBufferMethod::Host)
    require_gbuffer_method(config.gbuffer, level, visibility_choice(common, config.visibility));
  // rayquery on a device without it: refused before any device is created.
  if (config.visibility == lighting::VisibilitySetting::RayQuery)
    (void)visibility_choice(common, config.visibility);
  return config;
}

CLI::Option* add_integrator_option(CLI::App& cmd, std::string& integrator) {
  std::string footer = "Integrators:";
  for (const lighting::IntegratorEntry& entry : lighting::integrators()) {
    footer += fmt::format("\n  {:<10} {}", entry.name, entry.description);
  }
  cmd.footer(footer);
  return cmd.add_option("--integrator", integrator, lighting::integrator_names("|"));
}

lighting::VisibilitySetting visibility_setting(const CommonOptions& common) {
  lighting::VisibilitySetting setting = lighting::VisibilitySetting::Auto;
  for (const std::string& s : common.settings) {
    if (s.rfind("visibility=", 0) == 0) setting = lighting::parse_visibility_setting(s.substr(11));
  }
  return setting;
}

lighting::VisibilityChoice visibility_choice(const CommonOptions& common,
                                             lighting::VisibilitySetting setting) {
  const std::vector<runtime::DeviceInfo> devices = runtime::Device::enumerate();
  return lighting::choose_visibility(devices.at(runtime::select_device(devices, common.device)),
                                     setting);
}

lighting::GBufferMethod gbuffer_setting(const CommonOptions& common) {
  lighting::GBufferMethod method = lighting::GBufferMethod::Auto;
  for (const std::string& s : common.settings) {
    if (s.rfind("gbuffer=", 0) == 0) method = lighting::parse_gbuffer_method(s.substr(8));
  }
  return method;
}

void require_gbuffer_method(lighting::GBufferMethod method, const Level& level,
                            const lighting::VisibilityChoice& visibility) {
  if (method != lighting::GBufferMethod::Host) return;
  if (visibility.backend != lighting::VisibilityBackend::Host) {
    throw InputError(fmt::format(
        "--set gbuffer=host needs host visibility, but the frame would use visibility={} ({})",
        lighting::visibility_backend_name(visibility.backend), visibility.why));
  }
  if (!lighting::HostVisibility::answers(visibility.backend, lighting::bvh_instance_descs(level))) {
    throw InputError(
        "--set gbuffer=host: the level has alpha-tested materials, whose cutout only the raster "
        "G-buffer evaluates; use gbuffer=auto");
  }
}

std::pair<std::uint32_t, std::uint32_t> parse_size(std::string_view size) {
  const std::size_t x = size.find('x');
  if (x == std::string_view::npos)
    throw InputError(fmt::format("--size {}: expected WxH, e.g. 640x360", size));
  const std::uint32_t w = parse_dimension(size.substr(0, x), size);
  const std::uint32_t h = parse_dimension(size.substr(x + 1), size);
  // Per-pixel buffers (G-buffer, reservoirs, HDR) take ~200 bytes a pixel: cap at 4096^2 pixels
  // (3.3 GB) so an absurd size is a clear error, not an out-of-memory failure mid-run.
  if (std::uint64_t{w} * h > 4096ull * 4096ull)
    throw InputError(fmt::format("--size {}: {} pixels is more than the 4096x4096 limit", size,
                                 std::uint64_t{w} * h));
  return {w, h};
}

CLI::Option* add_render_scale_option(CLI::App& cmd, float& scale, const std::string& description) {
  return cmd.add_option("--render-scale", scale, description)
      ->check(CLI::Range(0.1f, 1.0f))
      ->capture_default_str();
}

void require_denoised_for_render_scale(float scale, lighting::FrameOutput output,
                                       std::string_view how_to_denoise) {
  if (scale < 1.0f && output == lighting::FrameOutput::Raw) {
    throw InputError(fmt::format(
        "--render-scale {} upscales the denoised image, and this output is raw (the integrator's "
        "unbiased image at --size): {}",
        scale, how_to_denoise));
  }
}

}  // namespace lantern::app
