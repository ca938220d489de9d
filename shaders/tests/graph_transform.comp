#version 460
// test.transform (render-graph GPU test): image(x, y) = 2 values[y * width + x] + 1.
layout(local_size_x = 8, local_size_y = 8) in;
layout(std430, binding = 0) readonly buffer ValuesBlock { uint data[]; } values;
layout(binding = 1, r32ui) uniform writeonly uimage2D image;
layout(push_constant) uniform Push { uint width; uint height; } pc;

void main() {
  const uvec2 p = gl_GlobalInvocationID.xy;
  if (p.x >= pc.width || p.y >= pc.height) return;
  imageStore(image, ivec2(p), uvec4(2u * values.data[p.y * pc.width + p.x] + 1u));
}
