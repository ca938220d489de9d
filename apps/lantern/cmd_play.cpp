// `lantern play [LEVEL]`: the level running in a window, playable (apps/lantern/play/): fly
// camera, the F1 panel (integrator, ReSTIR knobs, debug views, per-pass GPU graphs), flashlight,
// light groups, spawned lights, shader hot reload. Esc or closing the window quits; --frames N
// quits after N frames and --script FILE feeds timed key/mouse events (scripts, tests).
#include <fmt/format.h>

#include <memory>

#include "apps/lantern/commands.h"
#include "apps/lantern/play/play_session.h"
#include "engine/level/level_loader.h"

namespace lantern::app {
namespace {

struct PlayOptions {
  std::string level = "cornell_lights";
  std::string integrator = "restir";
  std::string script;
  bool panel = false;
  double target_ms = 33.0;
  bool size_given = false;  // --size on the command line (else the device picks)
};

void play(const PlayOptions& options, const CommonOptions& common) {
  PlayConfig config;
  config.level = options.level;
  const auto [width, height] = parse_size(common.size);
  config.width = options.size_given ? width : 0;
  config.height = options.size_given ? height : 0;
  config.dynamic_resolution.target_ms = options.target_ms;
  config.seed = common.seed;
  config.device = common.device;
  config.max_frames = common.frames > 0 ? static_cast<std::uint64_t>(common.frames) : 0;
  config.show_panel = options.panel;
  if (!options.script.empty()) config.script = InputScript::load(options.script);
  // Settings are validated here (InputError, exit 2) before any window opens.
  config.loaded_level = std::make_shared<const Level>(load_level_argument(options.level));
  config.integrator = integrator_config(options.integrator, common, *config.loaded_level);
  run_play(config);
}

}  // namespace

void add_play_command(CLI::App& root, CommonOptions& options) {
  auto play_options = std::make_shared<PlayOptions>();
  auto* cmd = root.add_subcommand("play", "Show a level running in a window (F1: panel)");
  cmd->add_option("level", play_options->level, "Level: a .json/.gltf/.glb path or a name")
      ->capture_default_str();
  add_integrator_option(*cmd, play_options->integrator)->capture_default_str();
  cmd->add_option("--script", play_options->script,
                  "Timed input events, e.g. 'frame 2 key W down' (see play_input.h)");
  cmd->add_flag("--panel", play_options->panel, "Start with the F1 panel open");
  cmd->add_option("--target-ms", play_options->target_ms,
                  "Frame-time target: dynamic resolution moves the internal size between 25% "
                  "and the window to hold it (0: off)")
      ->check(CLI::Range(0.0, 10000.0))
      ->capture_default_str();
  add_common_flags(*cmd, options);
  cmd->callback([play_options, &options, cmd] {
    play_options->size_given = cmd->count("--size") > 0;
    play(*play_options, options);
  });
}

}  // namespace lantern::app
