// A level's environment map (engine/scene/level.h EnvironmentMap: an equirectangular radiance
// file, intensity, rotation) read through OpenImageIO, with the importance-sampling tables of
// shaders/shared/environment.h: texels (radiance x intensity), the marginal alias table over rows
// and one conditional alias table per row, weights = luminance x exact texel solid angle.
// Built only when the level names an environment ("model only what a scene requires").
//
// Light selection: a light sample picks the environment with a fixed probability
// (environment_selection_probability) and otherwise the power alias table over the scene's
// emitters, so the environment acts as one more emitter with an estimated power
// 4 pi * mean luminance * pi R^2 (R = scene bounding-sphere radius): for each direction the flux
// through the scene's cross-section, the same proxy the directional lights use.
#pragma once

#include <cstdint>
#include <vector>

#include "engine/scene/level.h"
#include "runtime/image/image.h"
#include "runtime/runtime_fwd.h"
#include "shared/environment.h"

namespace lantern::lighting {

class EnvironmentDistribution {
 public:
  // From a lat-long image (rgb linear radiance; alpha ignored). InputError for an empty image or
  // non-finite / negative texels (named by pixel).
  EnvironmentDistribution(const runtime::ImageRGBA32F& image, float intensity,
                          const glm::quat& rotation);

  const gpu::GpuEnvironment& header() const { return header_; }
  const std::vector<gpu::vec4>& texels() const { return texels_; }
  const std::vector<gpu::AliasEntry>& marginal() const { return marginal_; }
  const std::vector<gpu::AliasEntry>& conditional() const { return conditional_; }
  gpu::EnvironmentView view() const {
    return {texels_.data(), marginal_.data(), conditional_.data()};
  }
  std::uint32_t width() const { return header_.size.x; }
  std::uint32_t height() const { return header_.size.y; }
  // Mean luminance of the radiance over the sphere (solid-angle weighted).
  float mean_luminance() const { return header_.params.y; }
  // Power proxy: 4 pi mean_luminance pi R^2 (see the file comment).
  double power_estimate(float scene_radius) const;

  // Reads level.path with OpenImageIO (InputError naming the file when it cannot be read).
  static EnvironmentDistribution load(const EnvironmentMap& level_environment);

 private:
  gpu::GpuEnvironment header_{};
  std::vector<gpu::vec4> texels_;
  std::vector<gpu::AliasEntry> marginal_;
  std::vector<gpu::AliasEntry> conditional_;
};

// P(pick the environment) = env_power / (env_power + lights_power); 1 without other emitters,
// 0 for a black map.
float environment_selection_probability(double env_power, double lights_power);

}  // namespace lantern::lighting
