// Log-average luminance exposure (auto_exposure.h).
#include "lighting/integrators/auto_exposure.h"

#include <cmath>

#include "shared/color.h"

namespace lantern::lighting {

float auto_exposure(const runtime::ImageRGBA32F& image) {
  constexpr double kFloor = 1e-4;  // keeps very dark pixels from dominating the log average
  double log_sum = 0.0;
  std::size_t count = 0;
  for (std::size_t i = 0; i + 3 < image.pixels.size(); i += 4) {
    const float l =
        gpu::luminance(glm::vec3(image.pixels[i], image.pixels[i + 1], image.pixels[i + 2]));
    if (!std::isfinite(l) || l <= 0.0f) continue;  // black: background, not the scene
    log_sum += std::log(kFloor + l);
    ++count;
  }
  if (count == 0) return 1.0f;
  return static_cast<float>(kExposureKey / std::exp(log_sum / static_cast<double>(count)));
}

}  // namespace lantern::lighting
