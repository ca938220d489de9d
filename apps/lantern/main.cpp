// `lantern`: entry point. Parses the command line (CLI11) and maps errors to exit codes:
// 0 success, 1 a failed run, 2 bad flag/value/file (one clear line on stderr), 3 budget exceeded.
#include <cstdio>
#include <exception>

#include "apps/lantern/commands.h"
#include "engine/core/error.h"
#include "engine/core/log.h"

namespace lantern::app {

void add_common_flags(CLI::App& cmd, CommonOptions& o) {
  cmd.add_option("--size", o.size, "Render size WxH")->capture_default_str();
  cmd.add_option("--seed", o.seed, "Random seed")->capture_default_str();
  cmd.add_option("--preset", o.preset, "Quality preset")
      ->check(CLI::IsMember({"fast", "balanced", "quality"}))
      ->capture_default_str();
  cmd.add_option(
      "--set", o.settings,
      "Override a setting KEY=VALUE (repeatable); visibility=auto|bvh|rayquery|host picks "
      "the ray tracing backend (auto: ray query on GPUs, Embree on the host answering the "
      "shading passes' shadow rays on CPU devices)");
  cmd.add_option("--device", o.device, "Vulkan device: auto|cpu|gpu|INDEX")->capture_default_str();
  cmd.add_option("--frames", o.frames, "Number of frames")->check(CLI::Range(1, 1000000));
  cmd.add_flag("--quiet", o.quiet, "Only print warnings and errors");
  cmd.parse_complete_callback([&o] {
    if (o.quiet) log::set_level(log::Level::Warning);
  });
}

}  // namespace lantern::app

int main(int argc, char** argv) {
  using namespace lantern;
  CLI::App root{"Lantern: real-time many-light rendering with ReSTIR", "lantern"};
  root.set_version_flag("--version", std::string("lantern ") + LANTERN_VERSION);
  root.require_subcommand(0, 1);
  app::CommonOptions options;
  app::add_devices_command(root, options);
  app::add_info_command(root, options);
  app::add_render_command(root, options);
  app::add_play_command(root, options);
  app::add_bench_command(root, options);
  app::add_capture_command(root, options);
  app::add_trade_command(root, options);

  try {
    root.parse(argc, argv);
    if (root.get_subcommands().empty()) {
      std::fputs(root.help().c_str(), stdout);
      return 0;
    }
  } catch (const CLI::CallForHelp& e) {
    return root.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return root.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return root.exit(e);
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "lantern: %s\n", e.what());
    return 2;
  } catch (const InputError& e) {
    std::fprintf(stderr, "lantern: %s\n", e.what());
    return 2;
  } catch (const app::BudgetExceeded& e) {
    std::fprintf(stderr, "lantern: %s\n", e.what());
    return 3;
  } catch (const RuntimeError& e) {
    std::fprintf(stderr, "lantern: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "lantern: internal error: %s\n", e.what());
    return 1;
  }
  return 0;
}
