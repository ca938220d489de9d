// perf.calibration: a fixed workload timed in the same run as a benchmark, so frame-time budgets
// can be written relative to it (engine/perf/budget.h). A mix like a lighting pass: a hash-driven
// gather from a 4 MiB table, a short dependent arithmetic chain, one buffer write per invocation.
// Reads/writes: its own buffers only. Dispatch: 1D, 64 invocations per workgroup.
#version 460

layout(local_size_x = 64) in;

layout(push_constant) uniform Push {
  uint count;   // invocations that write
  uint rounds;  // gather + arithmetic rounds per invocation
} push;

layout(std430, binding = 0) readonly buffer Table { vec4 values[]; } calibration_table;
layout(std430, binding = 1) writeonly buffer Result { vec4 values[]; } calibration_result;

uint hash(uint x) {
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return x;
}

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= push.count) return;
  uint table_size = uint(calibration_table.values.length());
  vec4 acc = vec4(0.0);
  uint h = hash(i);
  for (uint r = 0u; r < push.rounds; ++r) {
    h = hash(h + r);
    vec4 v = calibration_table.values[h % table_size];
    acc = fma(acc, vec4(0.999), v * inversesqrt(dot(v, v) + 1.0));
  }
  calibration_result.values[i] = acc;
}
