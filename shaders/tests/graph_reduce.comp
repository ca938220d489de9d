#version 460
// test.reduce (render-graph GPU test): sums[y] = sum over x of image(x, y); one thread per row.
layout(local_size_x = 64) in;
layout(binding = 0, r32ui) uniform readonly uimage2D image;
layout(std430, binding = 1) writeonly buffer SumsBlock { uint data[]; } sums;
layout(push_constant) uniform Push { uint width; uint height; } pc;

void main() {
  const uint y = gl_GlobalInvocationID.x;
  if (y >= pc.height) return;
  uint total = 0u;
  for (uint x = 0u; x < pc.width; ++x) total += imageLoad(image, ivec2(x, y)).x;
  sums.data[y] = total;
}
