// The integrators, one row each in integrator_registry.cpp: name, description, progressive or
// not, how to validate a configuration and how to make one. `lantern render --integrator NAME
// --preset P --set KEY=VALUE --spp N` becomes an IntegratorConfig naming a row; make_integrator()
// the Integrator (lighting/frame/frame_inputs.h) a FrameRenderer runs. Play (panel, number keys),
// the CLI (help text, the unknown-integrator error) and the tests list integrators from here.
// Adding an integrator is its own files plus one row. Each integrator validates its own settings
// (lantern::InputError naming an unknown key or a bad value, before any rendering).
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "lighting/frame/frame_inputs.h"
#include "lighting/gbuffer/gbuffer_method.h"
#include "runtime/runtime_fwd.h"

namespace lantern::lighting {

struct IntegratorConfig {
  std::string name = "baseline";  // a registry row's name
  std::string preset = "balanced";
  std::vector<std::pair<std::string, std::string>> settings;  // --set KEY=VALUE, in order
  std::uint32_t spp = 0;  // reference: samples per pixel per frame, 0 = its default
  // --set visibility=auto|bvh|rayquery|host (lighting/visibility/visibility_backend.h): resolved
  // against the device by make_integrator.
  VisibilitySetting visibility = VisibilitySetting::Auto;
  // --set gbuffer=auto|visibility|forward|host (lighting/gbuffer/gbuffer_method.h): the frame's
  // G-buffer method.
  GBufferMethod gbuffer = GBufferMethod::Auto;
  // --set denoise.KEY=VALUE (prefix stripped; lighting/denoise/denoise_settings.h), applied over
  // `preset` to the frame's denoiser, whichever integrator runs.
  std::vector<std::pair<std::string, std::string>> denoise;
};

struct IntegratorEntry {
  const char* name;         // --integrator NAME; bench, capture and trade JSON
  const char* description;  // one line for --help and the play panel
  // Its frames average to a converged image of a still scene: play accumulates them while the
  // camera, instances and lights stay put.
  bool progressive;
  // Checks `config` without a device (settings keys and values, spp): InputError naming the
  // problem, so a command refuses bad settings before creating a device or writing anything.
  void (*validate)(const IntegratorConfig& config);
  // The integrator configured by `config` (already validated), its tracing passes loaded for
  // `visibility` (make_integrator resolves config.visibility on the device).
  std::unique_ptr<Integrator> (*make)(runtime::Device& device, runtime::ShaderLibrary& shaders,
                                      const IntegratorConfig& config,
                                      VisibilityBackend visibility);
};

// Every integrator, in the order help text and play's number keys list them.
std::span<const IntegratorEntry> integrators();

// The row named `name`; InputError naming it and listing the valid names otherwise.
const IntegratorEntry& find_integrator(std::string_view name);

// The registry's names joined by `separator` ("restir|baseline|reference").
std::string integrator_names(std::string_view separator);

// find_integrator(config.name).validate(config).
void validate_integrator_config(const IntegratorConfig& config);

// The integrator `config` names, configured (validated first: InputError on an unknown name,
// unknown settings keys and bad values), with the visibility backend
// choose_visibility(device.info(), config.visibility) picks (InputError for rayquery on a device
// without it).
std::unique_ptr<Integrator> make_integrator(runtime::Device& device,
                                            runtime::ShaderLibrary& shaders,
                                            const IntegratorConfig& config);

}  // namespace lantern::lighting
