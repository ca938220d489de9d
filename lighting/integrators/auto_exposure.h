// Exposure for display images (PNG) of scenes whose radiance spans decades: maps the image's
// log-average luminance (Reinhard et al. 2002 "key") to middle grey.
#pragma once

#include "runtime/image/image.h"

namespace lantern::lighting {

// Middle grey the log-average luminance is mapped to.
inline constexpr float kExposureKey = 0.18f;

// kExposureKey / exp(mean(log(1e-4 + luminance))) over the finite, non-black pixels (black is
// background or full shadow and would drag the key down); 1 for an empty or black image.
float auto_exposure(const runtime::ImageRGBA32F& image);

}  // namespace lantern::lighting
