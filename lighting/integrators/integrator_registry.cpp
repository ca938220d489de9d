// The integrator registry (integrator_registry.h): one row per integrator.
#include "lighting/integrators/integrator_registry.h"

#include <fmt/format.h>

#include "engine/core/error.h"
#include "lighting/integrators/baseline_integrator.h"
#include "lighting/integrators/reference_integrator.h"
#include "lighting/restir/restir_integrator.h"

namespace lantern::lighting {
namespace {

using runtime::Device;
using runtime::ShaderLibrary;

// For integrators that shade one sample per pixel per frame: --spp above 1 is refused, saying
// what to do `instead`.
void require_one_spp(const IntegratorConfig& config, const char* instead) {
  if (config.spp <= 1) return;
  throw InputError(
      fmt::format("--spp {}: the {} integrator takes 1 sample per pixel per frame ({})", config.spp,
                  config.name, instead));
}

constexpr IntegratorEntry kIntegrators[] = {
    {.name = RestirIntegrator::kName,
     .description = "ReSTIR DI: candidates resampled with temporal and spatial reuse",
     .progressive = false,
     .validate =
         [](const IntegratorConfig& c) {
           require_one_spp(c, "set light_candidates, spatial_passes and neighbours instead");
           (void)make_restir_settings(c.preset, c.settings);
         },
     .make = [](Device& device, ShaderLibrary& shaders,
                const IntegratorConfig& c) -> std::unique_ptr<Integrator> {
       return std::make_unique<RestirIntegrator>(device, shaders,
                                                 make_restir_settings(c.preset, c.settings));
     }},
    {.name = BaselineIntegrator::kName,
     .description = "one power-sampled light and shadow ray per pixel (unbiased, noisy)",
     .progressive = true,
     .validate =
         [](const IntegratorConfig& c) {
           BaselineIntegrator::check_settings(c.settings);
           require_one_spp(c, "average frames with --frames N --average instead");
         },
     .make = [](Device& device, ShaderLibrary& shaders,
                const IntegratorConfig&) -> std::unique_ptr<Integrator> {
       return std::make_unique<BaselineIntegrator>(device, shaders);
     }},
    {.name = ReferenceIntegrator::kName,
     .description = "converged direct lighting, --spp MIS samples per pixel per frame",
     .progressive = true,
     .validate =
         [](const IntegratorConfig& c) { (void)parse_reference_settings(c.settings, c.spp); },
     .make = [](Device& device, ShaderLibrary& shaders,
                const IntegratorConfig& c) -> std::unique_ptr<Integrator> {
       return std::make_unique<ReferenceIntegrator>(device, shaders,
                                                    parse_reference_settings(c.settings, c.spp));
     }},
};

}  // namespace

std::span<const IntegratorEntry> integrators() {
  return kIntegrators;
}

const IntegratorEntry& find_integrator(std::string_view name) {
  for (const IntegratorEntry& entry : kIntegrators) {
    if (name == entry.name) return entry;
  }
  throw InputError(
      fmt::format("unknown integrator '{}' (integrators: {})", name, integrator_names(", ")));
}

std::string integrator_names(std::string_view separator) {
  std::string names;
  for (const IntegratorEntry& entry : kIntegrators) {
    if (!names.empty()) names += separator;
    names += entry.name;
  }
  return names;
}

void validate_integrator_config(const IntegratorConfig& config) {
  find_integrator(config.name).validate(config);
}

std::unique_ptr<Integrator> make_integrator(Device& device, ShaderLibrary& shaders,
                                            const IntegratorConfig& config) {
  const IntegratorEntry& entry = find_integrator(config.name);
  entry.validate(config);
  return entry.make(device, shaders, config);
}

}  // namespace lantern::lighting
