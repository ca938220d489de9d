#version 460
// Window/target test pattern (tests/window/): value(x, y) = (x / width, y / height,
// ((x + y + frame) % 7) / 8, 1) so every pixel and every frame is distinguishable on the CPU.
layout(local_size_x = 8, local_size_y = 8) in;

layout(set = 0, binding = 0, rgba32f) uniform writeonly image2D target;

layout(push_constant) uniform Push {
  uvec2 size;
  uint frame;
  uint pad;
} pc;

void main() {
  const uvec2 p = gl_GlobalInvocationID.xy;
  if (p.x >= pc.size.x || p.y >= pc.size.y) return;
  const vec2 uv = vec2(p) / vec2(pc.size);
  imageStore(target, ivec2(p), vec4(uv, float((p.x + p.y + pc.frame) % 7u) / 8.0, 1.0));
}
