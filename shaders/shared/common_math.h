// Scalar helpers and constants shared by the GLSL and C++ sides of the lighting math: pi,
// finite-value guards that survive fast-math (they test the exponent bits), safe division, and an
// orthonormal basis around a unit normal.
#ifndef LANTERN_SHARED_COMMON_MATH_H
#define LANTERN_SHARED_COMMON_MATH_H

#include "shared/lang.h"

LANTERN_BEGIN_SHARED

LANTERN_CONST float kPi = 3.14159265358979f;
LANTERN_CONST float kTwoPi = 6.28318530717959f;
LANTERN_CONST float kInvPi = 0.318309886183791f;

// True when x is neither NaN nor +-Inf (an all-ones exponent marks both).
LANTERN_FUNC bool is_finite(float x) {
  return (floatBitsToUint(x) & 0x7f800000u) != 0x7f800000u;
}

// x when it is finite and positive, else 0: the guard applied to every weight and pdf that
// enters a reservoir, so NaN, Inf and negative values can never propagate.
LANTERN_FUNC float finite_positive_or_zero(float x) {
  return (is_finite(x) && x > 0.0f) ? x : 0.0f;
}

// num / den, or 0 when the quotient would not be a finite non-negative number (0/0, x/0, Inf).
LANTERN_FUNC float safe_ratio(float num, float den) {
  return (den > 0.0f) ? finite_positive_or_zero(num / den) : 0.0f;
}

// Tangent t and bitangent b with (t, b, n) right-handed orthonormal, for a unit n
// (the branchless construction of Duff et al. 2017, "Building an Orthonormal Basis, Revisited").
LANTERN_FUNC void orthonormal_basis(vec3 n, LANTERN_OUT(vec3) t, LANTERN_OUT(vec3) b) {
  float s = n.z >= 0.0f ? 1.0f : -1.0f;
  float a = -1.0f / (s + n.z);
  float c = n.x * n.y * a;
  t = vec3(1.0f + s * n.x * n.x * a, s * c, -s * n.x);
  b = vec3(c, s + n.y * n.y * a, -n.y);
}

// World-space direction of the tangent-space vector v (z along n).
LANTERN_FUNC vec3 to_world(vec3 v, vec3 t, vec3 b, vec3 n) {
  return v.x * t + v.y * b + v.z * n;
}

LANTERN_END_SHARED

#endif
