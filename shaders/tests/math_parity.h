// GPU/CPU parity kernel for the shared math: one evaluation per index, compiled both into
// math_parity.comp (lavapipe) and into tests/shared_math/math_parity_gpu_test.cpp (CPU), which
// compares the two bit patterns. Every output is a uvec4 (floats as their bits) so nothing is
// canonicalised on the way out. Hostile weights (NaN, +Inf, negative) are streamed on purpose.
#ifndef LANTERN_TESTS_MATH_PARITY_H
#define LANTERN_TESTS_MATH_PARITY_H

#include "shared/brdf.h"
#include "shared/color.h"
#include "shared/lang.h"
#include "shared/reservoir.h"
#include "shared/reservoir_mis.h"
#include "shared/reservoir_pack.h"
#include "shared/rng.h"
#include "shared/sampling.h"

LANTERN_BEGIN_SHARED

LANTERN_CONST uint kMathParityOutputs = 6u;  // uvec4s written per index

LANTERN_FUNC uvec4 math_parity_bits(vec4 v) {
  return uvec4(floatBitsToUint(v.x), floatBitsToUint(v.y), floatBitsToUint(v.z),
               floatBitsToUint(v.w));
}

LANTERN_FUNC void math_parity_eval(uint index, LANTERN_OUT(uvec4) o0, LANTERN_OUT(uvec4) o1,
                                   LANTERN_OUT(uvec4) o2, LANTERN_OUT(uvec4) o3,
                                   LANTERN_OUT(uvec4) o4, LANTERN_OUT(uvec4) o5) {
  uint rng = rng_init(uvec2(index % 64u, index / 64u), 5u, 11u, 2u);
  uint first = rng_next_uint(rng);
  float uniform01 = rng_next_float(rng);

  // Reservoir streaming with one NaN, one +Inf and one negative weight among 8 candidates.
  Reservoir r = reservoir_empty();
  for (uint c = 0u; c < 8u; ++c) {
    float w = rng_next_float(rng) * 4.0f;
    if ((index & 7u) == c) w = uintBitsToFloat(0x7fc00000u);
    if (((index >> 3u) & 7u) == c) w = uintBitsToFloat(0x7f800000u);
    if (((index >> 6u) & 7u) == c) w = -w;
    vec2 uv = rng_next_vec2(rng);
    float target = rng_next_float(rng) + 0.1f;
    reservoir_update(r, light_sample_make(c, uv, target), w, rng_next_float(rng));
  }
  reservoir_finalize(r);
  PackedReservoir packed = reservoir_pack(r);
  o0 = uvec4(first, floatBitsToUint(uniform01), packed.light_age, packed.m_target);
  o1 = uvec4(floatBitsToUint(packed.W), packed.uv, floatBitsToUint(r.weight_sum),
             floatBitsToUint(r.M));

  // BRDF and sampling around a tilted normal.
  // One draw per statement: C++ leaves the order of argument evaluation unspecified.
  float nx = rng_next_float(rng) - 0.5f;
  float ny = rng_next_float(rng) - 0.5f;
  vec3 n = normalize(vec3(nx, ny, 1.0f));
  vec3 v = cosine_sample_hemisphere(n, rng_next_vec2(rng));
  // Roughness >= 0.1: below it the GGX peak is so narrow that D(h) is ill-conditioned in float
  // (one ulp of n.h moves D by over 1e-3) and GPU/CPU agree only in the sampled direction.
  float roughness = 0.1f + 0.9f * rng_next_float(rng);
  vec3 l = ggx_vndf_sample(n, v, roughness, rng_next_vec2(rng));
  o2 = math_parity_bits(vec4(l, ggx_vndf_pdf(n, v, l, roughness)));
  float red = rng_next_float(rng);
  float green = rng_next_float(rng);
  float blue = rng_next_float(rng);
  float metallic = rng_next_float(rng);
  float specular = rng_next_float(rng);
  vec3 f = brdf_eval(n, v, l, vec3(red, green, blue), roughness, metallic, specular);
  o3 = math_parity_bits(vec4(f, luminance(f)));

  vec3 bary = triangle_sample_barycentrics(rng_next_vec2(rng));
  vec3 p =
      triangle_point(vec3(0.0f, 0.0f, 2.0f), vec3(1.0f, 0.0f, 2.0f), vec3(0.0f, 1.0f, 2.5f), bary);
  float area =
      triangle_area(vec3(0.0f, 0.0f, 2.0f), vec3(1.0f, 0.0f, 2.0f), vec3(0.0f, 1.0f, 2.5f));
  o4 = math_parity_bits(vec4(bary, triangle_solid_angle_pdf(area, dot(p, p), 0.7f)));

  float cos_theta = rng_next_float(rng);
  float conf = 1.0f + float(index % 20u);
  o5 = math_parity_bits(vec4(spot_cone_falloff(cos_theta, 0.5f, 0.8f),
                             punctual_distance_falloff(1.0f + 4.0f * uniform01, 3.0f),
                             mis_pairwise_neighbour(conf, uniform01, 4.0f, cos_theta, 3.0f),
                             mis_weight_balance(conf, uniform01, conf * uniform01 + cos_theta)));
}

LANTERN_END_SHARED

#endif
