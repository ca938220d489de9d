// Texture sampling benchmark (tests/textures/texture_sampling_bench.cpp): each thread takes
// kTaps bilinear RGBA samples at scattered texcoords from one 512x512 sRGB texture and writes
// their sum. kHardware selects a combined image sampler (VK_FORMAT_R8G8B8A8_SRGB, linear filter,
// repeat: the driver's sampling path, what a bindless array would use per texture) or the
// project's software path (lib/textures.glsl's fetch + sRGB decode + bilinear on a storage
// buffer of packed texels).
#version 460
#extension GL_GOOGLE_include_directive : require

#include "shared/textures.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(constant_id = 0) const bool kHardware = false;
layout(constant_id = 1) const uint kTaps = 16u;

layout(binding = 0) uniform sampler2D bench_image;
layout(std430, binding = 1) readonly buffer Texels { uint w[]; } scene_texels;
layout(std430, binding = 2) readonly buffer Records { GpuTexture t[]; } scene_textures;
layout(std430, binding = 3) writeonly buffer Out { vec4 v[]; } bench_out;

#include "lib/textures.glsl"

void main() {
  uvec2 p = gl_GlobalInvocationID.xy;
  vec4 sum = vec4(0.0);
  vec2 uv = (vec2(p) + 0.5) / vec2(640.0, 360.0);
  for (uint k = 0u; k < kTaps; ++k) {
    vec2 q = fract(uv * 3.7 + vec2(0.137, 0.311) * float(k));
    sum += kHardware ? textureLod(bench_image, q, 0.0) : texture_sample(0u, q, 0.0);
  }
  bench_out.v[p.y * 640u + p.x] = sum;
}
