// Headless rendering of a level with a chosen integrator: N frames on the level's fixed camera,
// read back as linear radiance images (one per frame, or their mean), with GPU time per frame.
// What `lantern render` runs, and what the render tests call.
#pragma once

#include <cstdint>
#include <string_view>
#include <vector>

#include "engine/scene/level.h"
#include "runtime/image/image.h"

namespace lantern::runtime {
class Device;
class ShaderLibrary;
}  // namespace lantern::runtime

namespace lantern::lighting {

enum class IntegratorKind { Baseline, Reference, Restir };

// "baseline" | "reference" | "restir"; lantern::InputError naming the value otherwise.
IntegratorKind parse_integrator(std::string_view name);
const char* integrator_name(IntegratorKind kind);
// Throws lantern::InputError for an integrator that is not implemented yet (so a command can
// refuse before loading anything).
void require_implemented(IntegratorKind kind);

struct OfflineRenderRequest {
  IntegratorKind integrator = IntegratorKind::Baseline;
  std::uint32_t width = 640;
  std::uint32_t height = 360;
  std::uint32_t frames = 1;
  bool average = false;  // one image: the mean of the frames
  std::uint32_t seed = 1;
};

struct OfflineRenderResult {
  std::vector<runtime::ImageRGBA32F> images;  // one per frame, or one mean image
  std::vector<double> frame_ms;               // GPU time of each frame's passes
  double median_frame_ms() const;
};

// Renders `level` (static: instances at their load-time transforms, the level camera). Throws
// lantern::InputError for integrators not implemented yet and bad sizes.
OfflineRenderResult render_offline(runtime::Device& device, runtime::ShaderLibrary& shaders,
                                   const Level& level, const OfflineRenderRequest& request);

}  // namespace lantern::lighting
