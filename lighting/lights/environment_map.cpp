// Environment map loading and importance-sampling tables.
#include "lighting/lights/environment_map.h"

#include <fmt/format.h>

#include <cmath>
#include <glm/gtc/quaternion.hpp>
#include <span>
#include <string>

#include "engine/core/error.h"
#include "lighting/lights/alias_table.h"
#include "runtime/image/image_io.h"
#include "shared/color.h"

namespace lantern::lighting {
namespace {

// Alias entries for `weights`; a uniform table when they sum to zero (a black row is never
// picked by the marginal table, but its entries must still be valid).
std::vector<gpu::AliasEntry> alias_entries(const std::vector<float>& weights) {
  double sum = 0.0;
  for (float w : weights) sum += w;
  if (sum > 0.0) return AliasTable(weights).entries();
  return AliasTable(std::vector<float>(weights.size(), 1.0f)).entries();
}

}  // namespace

EnvironmentDistribution::EnvironmentDistribution(const runtime::ImageRGBA32F& image,
                                                 float intensity, const glm::quat& rotation) {
  const std::uint32_t w = image.width;
  const std::uint32_t h = image.height;
  if (w == 0 || h == 0 || image.pixels.size() != 4ull * w * h)
    throw InputError(fmt::format("environment map: empty or malformed image ({}x{})", w, h));
  if (!std::isfinite(intensity) || intensity < 0.0f)
    throw InputError(
        fmt::format("environment map: intensity {} must be finite and >= 0", intensity));
  const glm::mat4 map_to_world = glm::mat4_cast(glm::normalize(rotation));
  header_.map_to_world = map_to_world;
  header_.world_to_map = glm::transpose(map_to_world);
  header_.size = glm::uvec4(w, h, 0u, 0u);

  texels_.resize(std::size_t{w} * h);
  conditional_.resize(std::size_t{w} * h);
  std::vector<float> row_weights(h, 0.0f);
  std::vector<float> lum(w);
  double weighted_sum = 0.0;  // sum of luminance x solid angle
  for (std::uint32_t y = 0; y < h; ++y) {
    double row_sum = 0.0;
    for (std::uint32_t x = 0; x < w; ++x) {
      const float* p = image.at(x, y);
      const glm::vec3 rgb(p[0], p[1], p[2]);
      for (int c = 0; c < 3; ++c) {
        if (!std::isfinite(rgb[c]) || rgb[c] < 0.0f)
          throw InputError(fmt::format(
              "environment map: pixel ({}, {}) channel {} is {} (radiance must be finite and "
              ">= 0)",
              x, y, c, rgb[c]));
      }
      const glm::vec3 radiance = rgb * intensity;
      texels_[std::size_t{y} * w + x] = glm::vec4(radiance, 0.0f);
      lum[x] = std::max(gpu::luminance(radiance), 0.0f);
      row_sum += lum[x];
    }
    const std::vector<gpu::AliasEntry> row = alias_entries(lum);
    std::copy(row.begin(), row.end(), conditional_.begin() + std::ptrdiff_t{y} * w);
    const double texel_solid_angle = gpu::env_texel_solid_angle(header_, y);
    row_weights[y] = static_cast<float>(row_sum * texel_solid_angle);
    weighted_sum += row_sum * texel_solid_angle;
  }
  marginal_ = alias_entries(row_weights);
  const bool samplable = weighted_sum > 0.0 && std::isfinite(weighted_sum);
  header_.size.z = samplable ? 1u : 0u;
  header_.params = glm::vec4(0.0f, static_cast<float>(weighted_sum / (4.0 * M_PI)), 1.0f, 0.0f);
}

double EnvironmentDistribution::power_estimate(float scene_radius) const {
  const double r = scene_radius;
  return 4.0 * M_PI * static_cast<double>(mean_luminance()) * M_PI * r * r;
}

EnvironmentDistribution EnvironmentDistribution::load(const EnvironmentMap& level_environment) {
  runtime::ImageRGBA32F image;
  try {
    image = runtime::read_image(level_environment.path);
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    throw InputError(fmt::format("{}: cannot read environment map: {}",
                                 level_environment.path.string(), e.what()));
  }
  try {
    return EnvironmentDistribution(image, level_environment.intensity, level_environment.rotation);
  } catch (const InputError& e) {
    throw InputError(fmt::format("{}: {}", level_environment.path.string(), e.what()));
  }
}

float environment_selection_probability(double env_power, double lights_power) {
  if (!(env_power > 0.0) || !std::isfinite(env_power)) return 0.0f;
  if (!(lights_power > 0.0) || !std::isfinite(lights_power)) return 1.0f;
  return static_cast<float>(env_power / (env_power + lights_power));
}

}  // namespace lantern::lighting
