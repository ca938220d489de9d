// volume.restir_spatial: spatial reuse of the media reservoirs, then the final shading. Each
// pixel combines its reservoir with push.neighbours others from a disk of push.radius pixels
// (this frame's volume.restir_initial output) with the MIS weights of push.bias_correction
// (pairwise or the balance heuristic over the pixels' targets, each evaluated on its own
// pixel's ray: the keep-t shift; or 1/M), writes the result as this frame's
// final reservoir (next frame's history), and shades it unbiasedly:
//   radiance = radiance T(camera, surface) + W f(y) V T(camera, x) T(x, light)
// (lib/volume_scatter.glsl volume_sample_shade; its own random stream).
// Reads: "reservoirs_in", radiance, the scene. Writes: "reservoirs" (final), radiance (in
// place). Dispatch: one thread per pixel, 8x8 groups.
#version 460
#extension GL_GOOGLE_include_directive : require

#include "lib/scene_buffers.glsl"
#include "lib/volume_scatter.glsl"
#include "lib/volume_reservoir.glsl"
#include "shared/reservoir_mis.h"

layout(local_size_x = kVolumeGroupSize, local_size_y = kVolumeGroupSize) in;

layout(std430, binding = PASS_BINDING(0)) restrict readonly buffer In {
  VolumeReservoir r[];
} reservoirs_in;
layout(std430, binding = PASS_BINDING(1)) restrict writeonly buffer Out {
  VolumeReservoir r[];
} reservoirs;
layout(std430, binding = PASS_BINDING(2)) restrict buffer Radiance { vec4 pixels[]; } radiance;

layout(push_constant) uniform Push { VolumeRestirPush push; };

const uint kSet = kVolumeRestirMaxNeighbours + 1u;

void main() {
  uvec2 pixel = gl_GlobalInvocationID.xy;
  if (pixel.x >= push.width || pixel.y >= push.height) return;
  FrameConstants fc = frame_constants.frame;
  vec3 camera = fc.camera_position.xyz;
  uint index = pixel.y * push.width + pixel.x;
  MediaReservoir set[kSet];
  set[0] = media_reservoir_load(reservoirs_in.r[index]);
  vec3 dir = set[0].dir;
  float t_end = set[0].t_end;
  uint rng = frame_rng(pixel, kVolumeRngRestirSpatial);
  uint count = 1u;
  uint neighbours = min(push.neighbours, kVolumeRestirMaxNeighbours);
  for (uint n = 0u; n < neighbours; ++n) {
    vec2 u = rng_next_vec2(rng);
    float radius = push.radius * sqrt(u.x);
    ivec2 q = ivec2(pixel) + ivec2(round(radius * vec2(cos(kTwoPi * u.y), sin(kTwoPi * u.y))));
    if (q.x < 0 || q.y < 0 || q.x >= int(push.width) || q.y >= int(push.height) ||
        q == ivec2(pixel)) {
      continue;
    }
    set[count++] = media_reservoir_load(reservoirs_in.r[uint(q.y) * push.width + uint(q.x)]);
  }

  // MIS weights by the surfaces' bias_correction mode (shared/reservoir_mis.h): pairwise (O(k)
  // target evaluations), balance (O(k^2)), or none (1/M: biased where the pixels differ).
  MediaReservoir r = media_reservoir_empty(dir, t_end);
  float k = float(count - 1u);
  float m_total = 0.0;
  for (uint j = 0u; j < count; ++j) m_total += set[j].M;
  float w_sum = 0.0;
  for (uint i = 0u; i < count; ++i) {
    if (set[i].y.light == kInvalidLight || !(set[i].W > 0.0)) continue;
    float p_here = i == 0u ? set[0].target : volume_sample_target(set[i].y, camera, dir, t_end);
    if (!(p_here > 0.0)) continue;
    float m;
    if (push.bias_correction == kBiasCorrectionNone) {
      m = mis_weight_none(set[i].M, m_total);
    } else if (push.bias_correction == kBiasCorrectionPairwise) {
      if (i == 0u) {
        m = mis_pairwise_canonical_init(k);
        for (uint j = 1u; j < count; ++j) {
          float p_j = volume_sample_target(set[0].y, camera, set[j].dir, set[j].t_end);
          m += mis_pairwise_canonical_term(set[j].M, p_j, set[0].M, set[0].target, k);
        }
      } else {
        m = mis_pairwise_neighbour(set[i].M, set[i].target, set[0].M, p_here, k);
      }
    } else {
      float denominator = 0.0;
      for (uint j = 0u; j < count; ++j) {
        float p_j = j == i ? set[i].target
                           : (j == 0u ? p_here
                                      : volume_sample_target(set[i].y, camera, set[j].dir,
                                                             set[j].t_end));
        denominator += mis_balance_term(set[j].M, p_j);
      }
      m = mis_weight_balance(set[i].M, set[i].target, denominator);
    }
    if (media_reservoir_take(w_sum, m * p_here * set[i].W, rng)) {
      r.y = set[i].y;
      r.target = p_here;
    }
  }
  r.M = m_total;
  r.W = r.target > 0.0 ? w_sum / r.target : 0.0;
  if (!(r.target > 0.0 && r.W > 0.0)) r.y.light = kInvalidLight;
  reservoirs.r[index] = media_reservoir_store(r);

  uint shade_rng = frame_rng(pixel, kVolumeRngRestirShade);
  vec3 transmittance;
  vec3 inscattered =
      volume_sample_shade(r.y, camera, dir, t_end, true, shade_rng, transmittance);
  if (r.y.light != kInvalidLight) inscattered *= r.W;
  vec4 value = radiance.pixels[index];
  vec3 rgb = value.rgb * transmittance + inscattered;
  if (!(is_finite(rgb.x) && is_finite(rgb.y) && is_finite(rgb.z))) rgb = vec3(0.0);
  radiance.pixels[index] = vec4(max(rgb, vec3(0.0)), value.a);
}
