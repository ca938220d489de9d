// frame.output: the frame's HDR buffer (linear radiance, vec4 per pixel, row-major from the
// top-left) into the target's rgba32f output image: a linear copy (EXR, readback) or, with an
// exposure, the filmic tonemap of shared/tonemap.h (display-referred linear; target.present
// encodes sRGB). Non-finite values become 0. Reads: hdr. Writes: target. History: none.
// Dispatch: one thread per pixel, 8x8 groups.
#version 460
#extension GL_GOOGLE_include_directive : require

#include "frame/frame_output.h"
#include "shared/common_math.h"
#include "shared/tonemap.h"

layout(local_size_x = 8, local_size_y = 8) in;

layout(std430, binding = 0) readonly buffer HdrBuffer { vec4 pixels[]; } hdr;
layout(binding = 1, rgba32f) uniform writeonly image2D target;
layout(push_constant) uniform Push { FrameOutputPush push; };

void main() {
  uvec2 p = gl_GlobalInvocationID.xy;
  if (p.x >= push.width || p.y >= push.height) return;
  vec4 c = hdr.pixels[p.y * push.width + p.x];
  vec3 rgb = vec3(finite_positive_or_zero(c.r), finite_positive_or_zero(c.g),
                  finite_positive_or_zero(c.b));
  if (push.exposure > 0.0) {
    rgb = vec3(tonemap_filmic(rgb.r * push.exposure), tonemap_filmic(rgb.g * push.exposure),
               tonemap_filmic(rgb.b * push.exposure));
  }
  imageStore(target, ivec2(p), vec4(rgb, 1.0));
}
