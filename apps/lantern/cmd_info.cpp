// `lantern info LEVEL [--json FILE]`: what the level contains (CLI.md). What the engine enables
// for it (sampling structures, shader variants, memory) is added to LevelSummary::enabled by the
// lighting layer once it exists; this command prints whatever is there.
#include <fmt/format.h>

#include <cstdio>
#include <fstream>
#include <memory>

#include "apps/lantern/commands.h"
#include "engine/core/error.h"
#include "engine/level/level_loader.h"
#include "engine/scene/level_summary.h"

namespace lantern::app {
namespace {

struct InfoOptions {
  std::string level;
  std::string json;
};

void run_info(const InfoOptions& o) {
  const Level level = load_level_argument(o.level);
  const LevelSummary summary = summarize(level);
  std::fputs(to_text(summary).c_str(), stdout);
  if (!o.json.empty()) {
    std::ofstream out(o.json, std::ios::binary | std::ios::trunc);
    if (!out) throw InputError(fmt::format("{}: cannot write the --json file", o.json));
    out << to_json(summary).dump(2) << '\n';
    if (!out) throw RuntimeError(fmt::format("{}: write failed", o.json));
  }
}

}  // namespace

void add_info_command(CLI::App& root, CommonOptions& options) {
  auto opts = std::make_shared<InfoOptions>();
  auto* cmd = root.add_subcommand(
      "info", "Print what a level contains (and what the engine enables for it)");
  add_common_flags(*cmd, options);
  cmd->add_option("LEVEL", opts->level,
                  "Level: a .json/.gltf/.glb file or a name under content/levels/")
      ->required();
  cmd->add_option("--json", opts->json, "Also write the summary as JSON to FILE");
  cmd->callback([opts] { run_info(*opts); });
}

}  // namespace lantern::app
