#version 460
// Runs the shared-math parity kernel (math_parity.h) once per invocation; the CPU test runs the
// same function in C++ and compares (tests/shared_math/math_parity_gpu_test.cpp).
#extension GL_GOOGLE_include_directive : require

#include "tests/math_parity.h"

layout(local_size_x = 64) in;

layout(std430, binding = 0) writeonly buffer Results {
  uvec4 results[];
};
layout(push_constant) uniform Push {
  uint count;
};

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= count) {
    return;
  }
  uint base = i * kMathParityOutputs;
  math_parity_eval(i, results[base], results[base + 1u], results[base + 2u], results[base + 3u],
                   results[base + 4u], results[base + 5u]);
}
