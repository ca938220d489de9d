// Shared GLSL of the denoise.* passes (lighting/denoise/denoiser.h): push constants, the
// one-thread-per-pixel mapping, and the G-buffer reads the edge-stopping functions use. Each pass
// declares the G-buffer images it reads and its own buffers from PASS_BINDING(0) on.
#ifndef LANTERN_DENOISE_COMMON_GLSL
#define LANTERN_DENOISE_COMMON_GLSL

#include "shared/color.h"
#include "shared/common_math.h"
#include "shared/denoise.h"
#include "shared/gbuffer.h"

layout(local_size_x = kDenoiseGroupSize, local_size_y = kDenoiseGroupSize) in;

layout(push_constant) uniform Push { DenoisePush push; };

ivec2 denoise_size() { return ivec2(push.width, push.height); }

bool denoise_pixel(out ivec2 pixel) {
  pixel = ivec2(gl_GlobalInvocationID.xy);
  return pixel.x < int(push.width) && pixel.y < int(push.height);
}

uint denoise_index(ivec2 pixel) { return uint(pixel.y) * push.width + uint(pixel.x); }

bool denoise_inside(ivec2 q) { return all(greaterThanEqual(q, ivec2(0))) && all(lessThan(q, denoise_size())); }

vec3 denoise_finite(vec3 c) {
  return vec3(is_finite(c.r) ? c.r : 0.0, is_finite(c.g) ? c.g : 0.0, is_finite(c.b) ? c.b : 0.0);
}

#endif
