// `lantern devices`: placeholder until the runtime lands (issue 2).
#include "apps/lantern/commands.h"

namespace lantern::app {
void add_devices_command(CLI::App& root, CommonOptions& options) {
  auto* cmd = root.add_subcommand("devices", "List Vulkan devices with type and capabilities");
  add_common_flags(*cmd, options);
}
}  // namespace lantern::app
