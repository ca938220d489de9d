#version 460
// test.accumulate (render-graph GPU test): running = sums + last frame's running (when there is
// history: read through the graph's rgba32ui texel view of the history buffer, four per texel),
// copied to the host-readable buffer.
#extension GL_EXT_samplerless_texture_functions : require
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer SumsBlock { uint data[]; } sums;
layout(binding = 1) uniform utextureBuffer previous;
layout(std430, binding = 2) writeonly buffer RunningBlock { uint data[]; } running;
layout(std430, binding = 3) writeonly buffer ReadbackBlock { uint data[]; } readback;
layout(push_constant) uniform Push { uint count; uint has_history; } pc;

void main() {
  const uint i = gl_GlobalInvocationID.x;
  if (i >= pc.count) return;
  const uint value = sums.data[i] + (pc.has_history != 0u ? texelFetch(previous, int(i / 4u))[i % 4u] : 0u);
  running.data[i] = value;
  readback.data[i] = value;
}
