#version 460
// view.upload: copies display-referred pixels (tonemapped on the host, linear, [0,1]) from a
// host-written buffer into the target's output image. Reads: pixels. Writes: target.
// Dispatch: one thread per pixel, 8x8 groups.
layout(local_size_x = 8, local_size_y = 8) in;

layout(std430, set = 0, binding = 0) readonly buffer Pixels { vec4 pixels[]; };
layout(set = 0, binding = 1, rgba32f) uniform writeonly image2D target;
layout(push_constant) uniform Push { uvec2 size; } push;

void main() {
  uvec2 p = gl_GlobalInvocationID.xy;
  if (p.x >= push.size.x || p.y >= push.size.y) return;
  imageStore(target, ivec2(p), pixels[p.y * push.size.x + p.x]);
}
