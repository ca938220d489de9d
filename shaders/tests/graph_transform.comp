#version 460
// test.transform (render-graph GPU test): image(x, y) = 2 values[y * width + x] + 1, the values
// read through the graph's rgba32ui texel view of a transient buffer (four per texel).
#extension GL_EXT_samplerless_texture_functions : require
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0) uniform utextureBuffer values;
layout(binding = 1, r32ui) uniform writeonly uimage2D image;
layout(push_constant) uniform Push { uint width; uint height; } pc;

void main() {
  const uvec2 p = gl_GlobalInvocationID.xy;
  if (p.x >= pc.width || p.y >= pc.height) return;
  const uint i = p.y * pc.width + p.x;
  imageStore(image, ivec2(p), uvec4(2u * texelFetch(values, int(i / 4u))[i % 4u] + 1u));
}
