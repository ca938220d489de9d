// Choosing and configuring an integrator by name: `lantern render --integrator K --preset P
// --set KEY=VALUE --spp N` becomes an IntegratorConfig, make_integrator() the Integrator
// (lighting/frame/frame_inputs.h) a FrameRenderer runs. Each integrator validates its own settings
// (lantern::InputError naming an unknown key or a bad value, before any rendering).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "lighting/frame/frame_inputs.h"

namespace lantern::runtime {
class Device;
class ShaderLibrary;
}  // namespace lantern::runtime

namespace lantern::lighting {

enum class IntegratorKind { Baseline, Reference, Restir };

// "baseline" | "reference" | "restir"; lantern::InputError naming the value otherwise.
IntegratorKind parse_integrator(std::string_view name);
const char* integrator_name(IntegratorKind kind);

struct IntegratorConfig {
  IntegratorKind kind = IntegratorKind::Baseline;
  std::string preset = "balanced";
  std::vector<std::pair<std::string, std::string>> settings;  // --set KEY=VALUE, in order
  std::uint32_t spp = 0;  // reference: samples per pixel per frame, 0 = its default
};

// Checks `config` without a device (settings keys and values, spp): InputError naming the
// problem, so a command refuses bad settings before creating a device or writing anything.
void validate_integrator_config(const IntegratorConfig& config);

// The integrator `config` names, configured; InputError on unknown settings keys, bad values and
// integrators not implemented yet.
std::unique_ptr<Integrator> make_integrator(runtime::Device& device,
                                            runtime::ShaderLibrary& shaders,
                                            const IntegratorConfig& config);

}  // namespace lantern::lighting
