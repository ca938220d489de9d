// `lantern devices [--json FILE]`: every Vulkan device with its type, Vulkan version and the
// capabilities Lantern cares about; marks the one `--device` selects.
#include <fmt/format.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "apps/lantern/commands.h"
#include "engine/core/error.h"
#include "runtime/core/device.h"

namespace lantern::app {
namespace {

std::string gib(std::uint64_t bytes) {
  return fmt::format("{:.1f} GiB", static_cast<double>(bytes) / (1ull << 30));
}
const char* yes_no(bool value) {
  return value ? "yes" : "no";
}

void run_devices(const CommonOptions& options, const std::string& json_path) {
  const auto devices = runtime::Device::enumerate();
  const std::uint32_t selected =
      runtime::select_device(devices, options.device);  // InputError if bad
  for (const auto& d : devices) {
    fmt::print("{}{}: {}\n", d.index == selected ? "*" : " ", d.index, d.name);
    fmt::print("    type {}, Vulkan {}, driver {}\n", d.type, d.api_version, d.driver);
    fmt::print("    ray query {}, descriptor indexing {}, push descriptors {}, memory {}\n",
               yes_no(d.ray_query), yes_no(d.descriptor_indexing), yes_no(d.push_descriptor),
               gib(d.device_local_bytes));
  }
  fmt::print("* = selected by --device {}\n", options.device);

  if (json_path.empty()) return;
  nlohmann::json list = nlohmann::json::array();
  for (const auto& d : devices)
    list.push_back({{"index", d.index},
                    {"name", d.name},
                    {"type", d.type},
                    {"api_version", d.api_version},
                    {"driver", d.driver},
                    {"ray_query", d.ray_query},
                    {"descriptor_indexing", d.descriptor_indexing},
                    {"push_descriptor", d.push_descriptor},
                    {"memory_bytes", d.device_local_bytes}});
  const nlohmann::json doc = {
      {"devices", list}, {"selected", selected}, {"selector", options.device}};
  std::ofstream out(json_path);
  out << doc.dump(2) << '\n';
  if (!out) throw InputError(fmt::format("--json {}: cannot write file", json_path));
}

}  // namespace

void add_devices_command(CLI::App& root, CommonOptions& options) {
  auto* cmd = root.add_subcommand("devices", "List Vulkan devices with type and capabilities");
  add_common_flags(*cmd, options);
  auto json_path = std::make_shared<std::string>();
  cmd->add_option("--json", *json_path, "Also write the list as JSON to FILE");
  cmd->callback([&options, json_path] { run_devices(options, *json_path); });
}

}  // namespace lantern::app
