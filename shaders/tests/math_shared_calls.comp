#version 460
// Build-time check that the shared math (shaders/shared/) generates valid SPIR-V when called:
// glslang drops uncalled functions, so this shader calls each one once and stores the results.
#extension GL_GOOGLE_include_directive : require

#include "shared/brdf.h"
#include "shared/color.h"
#include "shared/reservoir.h"
#include "shared/reservoir_mis.h"
#include "shared/reservoir_pack.h"
#include "shared/rng.h"
#include "shared/sampling.h"

layout(local_size_x = 8, local_size_y = 8) in;

layout(std430, binding = 0) buffer Out {
  PackedReservoir packed_out[];
};
layout(std430, binding = 1) buffer Floats {
  vec4 floats_out[];
};

void main() {
  uvec2 pixel = gl_GlobalInvocationID.xy;
  uint index = pixel.y * 64u + pixel.x;
  uint rng = rng_init(pixel, 3u, 1u, 0u);
  vec3 n = vec3(0.0f, 0.0f, 1.0f);
  vec3 v = normalize(vec3(0.3f, 0.1f, 1.0f));

  Reservoir r = reservoir_empty();
  for (uint i = 0u; i < 4u; ++i) {
    vec3 l = cosine_sample_hemisphere(n, rng_next_vec2(rng));
    vec3 f = brdf_eval(n, v, l, vec3(0.8f), 0.5f, 0.0f, 1.0f);
    float p_hat = luminance(f);
    float w = mis_weight_none(1.0f, 4.0f) * safe_ratio(p_hat, cosine_hemisphere_pdf(n, l));
    reservoir_update(r, light_sample_make(i, rng_next_vec2(rng), p_hat), w, rng_next_float(rng));
  }
  reservoir_finalize(r);
  Reservoir neighbour = reservoir_unpack(packed_out[index ^ 1u]);
  float k = 1.0f;
  float m_c = mis_pairwise_canonical_init(k) +
              mis_pairwise_canonical_term(neighbour.M, 0.5f, r.M, r.selected.target_pdf, k);
  float m_i = mis_pairwise_neighbour(neighbour.M, neighbour.selected.target_pdf, r.M, 0.5f, k);
  float m_b = mis_weight_balance(r.M, r.selected.target_pdf,
                                 mis_balance_term(r.M, r.selected.target_pdf) +
                                     mis_balance_term(neighbour.M, 0.5f));
  Reservoir combined = reservoir_empty();
  reservoir_merge(combined, r, m_c, r.selected.target_pdf, rng_next_float(rng));
  reservoir_merge(combined, neighbour, m_i, 0.5f, rng_next_float(rng));
  reservoir_finalize(combined);
  reservoir_cap_m(combined, 20.0f);
  packed_out[index] = reservoir_pack(combined);

  vec3 h = ggx_vndf_sample(n, v, 0.3f, rng_next_vec2(rng));
  vec3 bary = triangle_sample_barycentrics(rng_next_vec2(rng));
  vec3 p = triangle_point(vec3(0.0f), vec3(1.0f, 0.0f, 0.0f), vec3(0.0f, 1.0f, 0.0f), bary);
  float area = triangle_area(vec3(0.0f), vec3(1.0f, 0.0f, 0.0f), vec3(0.0f, 1.0f, 0.0f));
  floats_out[index] = vec4(ggx_vndf_pdf(n, v, h, 0.3f) + m_b,
                           triangle_solid_angle_pdf(area, dot(p, p), 0.5f),
                           spot_cone_falloff(0.9f, 0.8f, 0.95f) * punctual_distance_falloff(4.0f, 0.0f),
                           float(reservoir_has_sample(combined)) +
                               directional_light_to_light(vec3(0.0f, -1.0f, 0.0f)).y);
}
