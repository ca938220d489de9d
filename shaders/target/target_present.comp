#version 460
// target.present (runtime/target/present_pass.cpp): copies the target's linear output image to
// the swapchain image, scaled by nearest sampling when the sizes differ, clamped to [0,1] and
// sRGB-encoded (the swapchain is UNORM: storage on *_SRGB formats is rarely supported).
// Reads: source (rgba32f). Writes: destination (swapchain, any 8-bit UNORM format).
// Dispatch: one thread per destination pixel, 8x8 groups.
#extension GL_GOOGLE_include_directive : require
#include "shared/tonemap.h"

layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0, rgba32f) uniform readonly image2D source;
layout(set = 0, binding = 1) uniform writeonly image2D destination;

layout(push_constant) uniform Push {
  uvec2 source_size;
  uvec2 destination_size;
} pc;

void main() {
  const uvec2 p = gl_GlobalInvocationID.xy;
  if (p.x >= pc.destination_size.x || p.y >= pc.destination_size.y) return;
  const uvec2 s = min(uvec2((vec2(p) + 0.5) * vec2(pc.source_size) / vec2(pc.destination_size)),
                      pc.source_size - 1u);
  const vec4 linear = imageLoad(source, ivec2(s));
  vec3 encoded;
  for (int i = 0; i < 3; ++i) encoded[i] = srgb_encode(linear[i]);
  imageStore(destination, ivec2(p), vec4(encoded, 1.0));
}
