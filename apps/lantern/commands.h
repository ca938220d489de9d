// The `lantern` command's subcommands (shared/CLI.md). Each lives in its own cmd_*.cpp and
// registers itself on the root app; `run` callbacks throw lantern::InputError for bad input
// (exit 2) and lantern::RuntimeError for a failed run (exit 1).
#pragma once

#include <CLI/CLI.hpp>

#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace lantern::app {

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

// "640x360" -> (640, 360); InputError naming the flag otherwise.
std::pair<std::uint32_t, std::uint32_t> parse_size(std::string_view size);

}  // namespace lantern::app
