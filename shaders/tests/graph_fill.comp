#version 460
// test.fill (render-graph GPU test, tests/graph/graph_gpu_test.cpp): values[i] = 3 i + seed.
layout(local_size_x = 64) in;
layout(std430, binding = 0) writeonly buffer ValuesBlock { uint data[]; } values;
layout(push_constant) uniform Push { uint count; uint seed; } pc;

void main() {
  const uint i = gl_GlobalInvocationID.x;
  if (i >= pc.count) return;
  values.data[i] = 3u * i + pc.seed;
}
