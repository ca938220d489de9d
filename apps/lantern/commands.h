// The `lantern` command's subcommands (shared/CLI.md). Each lives in its own cmd_*.cpp and
// registers itself on the root app; `run` callbacks throw lantern::InputError for bad input
// (exit 2) and lantern::RuntimeError for a failed run (exit 1).
#pragma once

#include <CLI/CLI.hpp>

#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "engine/scene/level.h"
#include "lighting/frame/frame_renderer.h"
#include "lighting/integrators/integrator_registry.h"

namespace lantern::app {

// A benchmark ran but exceeded its budget: exit code 3 (CLI.md).
class BudgetExceeded : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Flags shared by every command (CLI.md "Common flags").
struct CommonOptions {
  std::string size = "640x360";
  std::uint32_t seed = 1;
  std::string preset = "balanced";
  std::vector<std::string> settings;  // --set KEY=VALUE, repeatable
  std::string device = "auto";
  int frames = -1;  // -1: the command's default
  bool quiet = false;
};

// Adds the common flags to a subcommand.
void add_common_flags(CLI::App& cmd, CommonOptions& options);

void add_devices_command(CLI::App& root, CommonOptions& options);
void add_info_command(CLI::App& root, CommonOptions& options);
void add_render_command(CLI::App& root, CommonOptions& options);
void add_play_command(CLI::App& root, CommonOptions& options);

void add_bench_command(CLI::App& root, CommonOptions& options);
void add_capture_command(CLI::App& root, CommonOptions& options);
void add_trade_command(CLI::App& root, CommonOptions& options);

// The integrator configuration a command runs: `integrator` by name, the --preset, the level's
// settings block for that integrator ("restir.radius" in the level is "radius" for restir), then
// every --set in order (a "restir." prefix is optional; settings for another integrator are
// skipped with a warning); `visibility` (auto|bvh|rayquery) goes to config.visibility. InputError
// for a malformed --set, an unknown visibility value or an unknown integrator.
lighting::IntegratorConfig integrator_config(const std::string& integrator,
                                             const CommonOptions& common, const Level& level);

// The --integrator option of a command: the registry's names in its help, and one line per
// integrator (name and description) in the command's help footer.
CLI::Option* add_integrator_option(CLI::App& cmd, std::string& integrator);
// The last --set visibility=auto|bvh|rayquery (auto without one); InputError on another value.
lighting::VisibilitySetting visibility_setting(const CommonOptions& common);
// The visibility backend `setting` picks on the device --device selects (enumerated, not created);
// InputError for rayquery on a device without it.
lighting::VisibilityChoice visibility_choice(const CommonOptions& common,
                                             lighting::VisibilitySetting setting);

// The last --set gbuffer=auto|visibility|forward|host (auto without one); InputError on another
// value (no device work).
lighting::GBufferMethod gbuffer_setting(const CommonOptions& common);
// InputError when `method` cannot run for `level` on `visibility` (the choice the device makes):
// host needs the host backend and no alpha-tested material (HostVisibility::answers).
void require_gbuffer_method(lighting::GBufferMethod method, const Level& level,
                            const lighting::VisibilityChoice& visibility);

// "640x360" -> (640, 360); InputError naming the flag otherwise.
std::pair<std::uint32_t, std::uint32_t> parse_size(std::string_view size);

// --render-scale S (0.1..1, default 1): the internal size as a fraction of --size, upscaled back
// by upscale.temporal (what `play`'s dynamic resolution moves); `description` is its help.
CLI::Option* add_render_scale_option(CLI::App& cmd, float& scale, const std::string& description);
// render and capture: a scale below 1 shapes the denoised image only (the raw one is the
// integrator's unbiased image at --size). InputError naming --render-scale and `how_to_denoise`
// (the flags that choose the denoised output) when `output` is raw.
void require_denoised_for_render_scale(float scale, lighting::FrameOutput output,
                                       std::string_view how_to_denoise);

}  // namespace lantern::app
