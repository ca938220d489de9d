// Runtime smoke test: writes values[i] = i * kMultiplier + offset for i < count.
// Exercises a spec-constant workgroup size, a named spec constant and push constants.
#version 460

layout(local_size_x_id = 0) in;
layout(constant_id = 1) const uint kMultiplier = 3u;

layout(push_constant) uniform Push {
  uint count;
  uint offset;
} pc;

layout(std430, set = 0, binding = 0) writeonly buffer Result {
  uint values[];
} result;

void main() {
  const uint i = gl_GlobalInvocationID.x;
  if (i >= pc.count) return;
  result.values[i] = i * kMultiplier + pc.offset;
}
