// Display transform shared by the GPU tonemap pass and the CPU PNG writer: exposure, a filmic
// curve (rational fit of an ACES-like response, white point kWhite), then the sRGB OETF.
// EXR output never passes through here: it stays linear radiance.
#ifndef LANTERN_SHARED_TONEMAP_H
#define LANTERN_SHARED_TONEMAP_H

#include "shared/lang.h"

LANTERN_BEGIN_SHARED

// Filmic shoulder: f(x) = x(ax + b) / (x(cx + d) + e), normalised so f(kWhite) = 1.
LANTERN_CONST float kTonemapA = 2.51f;
LANTERN_CONST float kTonemapB = 0.03f;
LANTERN_CONST float kTonemapC = 2.43f;
LANTERN_CONST float kTonemapD = 0.59f;
LANTERN_CONST float kTonemapE = 0.14f;

LANTERN_FUNC float tonemap_filmic(float x) {
  x = max(x, 0.0f);
  float y = (x * (kTonemapA * x + kTonemapB)) / (x * (kTonemapC * x + kTonemapD) + kTonemapE);
  return clamp(y, 0.0f, 1.0f);
}

LANTERN_FUNC float srgb_encode(float linear) {
  float c = clamp(linear, 0.0f, 1.0f);
  return c <= 0.0031308f ? 12.92f * c : 1.055f * pow(c, 1.0f / 2.4f) - 0.055f;
}

// Linear radiance -> display-referred sRGB in [0,1]. Non-finite input maps to 0.
LANTERN_FUNC vec3 tonemap_to_srgb(vec3 radiance, float exposure) {
  vec3 result = vec3(0.0f);
  for (int i = 0; i < 3; ++i) {
    float v = radiance[i] * exposure;
    if (isnan(v) || isinf(v)) v = 0.0f;
    result[i] = srgb_encode(tonemap_filmic(v));
  }
  return result;
}

LANTERN_END_SHARED

#endif
