// Integrator names and make_integrator (integrator_factory.h).
#include "lighting/integrators/integrator_factory.h"

#include <fmt/format.h>

#include "engine/core/error.h"
#include "lighting/integrators/baseline_integrator.h"
#include "lighting/integrators/reference_integrator.h"
#include "lighting/restir/restir_integrator.h"

namespace lantern::lighting {

IntegratorKind parse_integrator(std::string_view name) {
  if (name == "baseline") return IntegratorKind::Baseline;
  if (name == "reference") return IntegratorKind::Reference;
  if (name == "restir") return IntegratorKind::Restir;
  throw InputError(
      fmt::format("unknown integrator '{}' (expected restir, baseline or reference)", name));
}

const char* integrator_name(IntegratorKind kind) {
  switch (kind) {
    case IntegratorKind::Baseline:
      return "baseline";
    case IntegratorKind::Reference:
      return "reference";
    case IntegratorKind::Restir:
      return "restir";
  }
  return "?";
}

void validate_integrator_config(const IntegratorConfig& config) {
  switch (config.kind) {
    case IntegratorKind::Baseline:
      if (!config.settings.empty()) {
        throw InputError(fmt::format(
            "--set {}: the baseline integrator has no settings (1 sample per pixel per frame)",
            config.settings.front().first));
      }
      if (config.spp > 1) {
        throw InputError(fmt::format(
            "--spp {}: the baseline integrator takes 1 sample per pixel per frame (average "
            "frames with --frames N --average instead)",
            config.spp));
      }
      return;
    case IntegratorKind::Reference:
      (void)parse_reference_settings(config.settings, config.spp);
      return;
    case IntegratorKind::Restir:
      if (config.spp > 1) {
        throw InputError(fmt::format(
            "--spp {}: the restir integrator shades 1 sample per pixel per frame (set "
            "light_candidates, spatial_passes and neighbours with --set instead)",
            config.spp));
      }
      (void)make_restir_settings(config.preset, config.settings);
      return;
  }
  throw InputError(fmt::format("unknown integrator kind {}", static_cast<int>(config.kind)));
}

std::unique_ptr<Integrator> make_integrator(runtime::Device& device,
                                            runtime::ShaderLibrary& shaders,
                                            const IntegratorConfig& config) {
  validate_integrator_config(config);
  switch (config.kind) {
    case IntegratorKind::Baseline:
      return std::make_unique<BaselineIntegrator>(device, shaders);
    case IntegratorKind::Reference:
      return std::make_unique<ReferenceIntegrator>(
          device, shaders, parse_reference_settings(config.settings, config.spp));
    case IntegratorKind::Restir:
      return std::make_unique<RestirIntegrator>(
          device, shaders, make_restir_settings(config.preset, config.settings));
  }
  throw InputError(fmt::format("unknown integrator kind {}", static_cast<int>(config.kind)));
}

}  // namespace lantern::lighting
