// `lantern info LEVEL [--json FILE]`: what the level contains (CLI.md) and what the lighting
// module builds for it, why, and the memory each part takes (lighting/scene/scene_requirements.h)
// at the --size given.
#include <fmt/format.h>

#include <cstdio>
#include <fstream>
#include <memory>

#include "apps/lantern/commands.h"
#include "engine/core/error.h"
#include "engine/level/level_loader.h"
#include "engine/scene/level_summary.h"
#include "lighting/scene/scene_requirements.h"

namespace lantern::app {
namespace {

struct InfoOptions {
  std::string level;
  std::string json;
};

void run_info(const InfoOptions& o, const CommonOptions& common) {
  const Level level = load_level_argument(o.level);
  LevelSummary summary = summarize(level);
  const auto [width, height] = parse_size(common.size);
  // The backend the frame would pick on the --device (enumerated only; bvh when none is found).
  lighting::VisibilityChoice visibility{lighting::VisibilityBackend::Bvh, "no Vulkan device"};
  const lighting::VisibilitySetting setting = visibility_setting(common);
  const lighting::GBufferMethod gbuffer = gbuffer_setting(common);  // before any device work
  try {
    visibility = visibility_choice(common, setting);
  } catch (const RuntimeError&) {
    if (setting == lighting::VisibilitySetting::RayQuery) throw;
  }
  require_gbuffer_method(gbuffer, level, visibility);
  lighting::describe_requirements(level, width, height, summary, visibility, gbuffer);
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
  cmd->callback([opts, &options] { run_info(*opts, options); });
}

}  // namespace lantern::app
