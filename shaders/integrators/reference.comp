// integrators.reference: converged direct lighting, the yardstick of baseline and ReSTIR. Per
// pixel: the G-buffer's primary hit (the same surface baseline and ReSTIR shade), its emission
// seen from the camera (or the environment on sky pixels), then `spp` samples, each one light
// sample and one BSDF sample combined with the power heuristic (MIS, Veach 1995):
//   light sampling: the environment with probability env.params.x (its luminance x solid-angle
//     distribution, shared/environment.h), else one emitter from the power alias table (triangles:
//     uniform area point, solid-angle pdf; punctual lights: delta, weight 1); one shadow ray;
//   BSDF sampling: GGX visible normals or cosine-weighted Lambert, picked by an estimate of the
//     lobes' albedos; the ray's closest hit adds a front-facing emissive triangle's radiance, a
//     miss adds the environment.
// Both strategies' pdfs are evaluated for every direction that either can produce, so emissive
// triangles and the environment are counted once. Direct lighting only (no bounces).
// Analytic lights (point, spot, directional; the light list's tail after the emissive triangles)
// are estimated apart when there are at most kReferenceAnalyticWalkMax of them and
// kReferenceAnalyticWalkPerSample per sample (integrators/reference.h): per pixel, `spp`
// stratified picks from all of them in proportion to each one's unshadowed contribution at the
// point (two walks through the list: the total, then the picks), one shadow ray per light
// picked. That estimate is exact but for visibility (and the media's transmittance), where the
// power alias table picks a weak light beside the point about once in 10^4-10^5 samples
// (night_market: the old reference's two seeds differed by a relMSE of 0.27 at 2048 spp); the
// alias draws that land on an analytic light then count 0.
// Reads: G-buffer images (shared/gbuffer.h) and the scene (lib/scene_buffers.glsl: frame
// constants, geometry, materials, lights, the environment map — a black 1-texel stand-in when the
// level has none — and the BVH through lib/visibility.glsl).
// Writes: radiance (rgba32f per pixel, the mean of this dispatch's samples). History: none (the
// host averages frames). Dispatch: a 1D grid of tiles (lib/pixel_groups.glsl's shape), shuffled
// (push.tile_stride), as integrators.baseline.
#version 460
#extension GL_GOOGLE_include_directive : require

#include "lib/pixel_groups.glsl"
#include "lib/scene_buffers.glsl"
#include "lib/emitter_hit.glsl"
#include "integrators/reference.h"
#include "shared/alias_table.h"
#include "shared/brdf.h"
#include "shared/color.h"
#include "shared/common_math.h"
#include "shared/environment.h"
#include "shared/gbuffer.h"
#include "shared/light_eval.h"
#include "shared/lights.h"
#include "shared/rng.h"
#include "shared/sampling.h"
#include "shared/scene.h"
#include "shared/textures.h"

layout(std430, binding = PASS_BINDING(0)) writeonly buffer RadianceBuffer {
  vec4 pixels[];
} radiance;
layout(binding = PASS_BINDING(1), rgba32f) uniform readonly image2D gbuffer_position;
layout(binding = PASS_BINDING(2), rgba32f) uniform readonly image2D gbuffer_normal;
layout(binding = PASS_BINDING(3), rgba32f) uniform readonly image2D gbuffer_emission_metallic;
layout(binding = PASS_BINDING(4), rgba32ui) uniform readonly uimage2D gbuffer_ids;
layout(binding = PASS_BINDING(5), rgba16f) uniform readonly image2D gbuffer_albedo_roughness;
layout(push_constant) uniform Push { ReferencePush push; };

// Shading frame and lobe choice at one surface point.
struct Shading {
  vec3 x;
  vec3 n;      // shading normal on the viewer's side
  vec3 ng;     // geometric normal on the viewer's side
  vec3 v;      // towards the viewer
  vec3 albedo;
  float roughness;
  float metallic;
  float specular;
  float p_specular;  // probability that BSDF sampling picks the GGX lobe
};

float bsdf_pdf(Shading sh, vec3 l) {
  float p = 0.0;
  if (sh.p_specular > 0.0) p += sh.p_specular * ggx_vndf_pdf(sh.n, sh.v, l, sh.roughness);
  if (sh.p_specular < 1.0) p += (1.0 - sh.p_specular) * cosine_hemisphere_pdf(sh.n, l);
  return p;
}

vec3 brdf(Shading sh, vec3 l) {
  if (dot(sh.ng, l) <= 0.0) return vec3(0.0);  // below the geometric surface: no light
  return brdf_eval(sh.n, sh.v, l, sh.albedo, sh.roughness, sh.metallic, sh.specular);
}

// The first light analytic_lights() estimates: the first analytic light when there are at most
// kReferenceAnalyticWalkMax and kReferenceAnalyticWalkPerSample per sample, else none (the alias
// table draws them all).
uint analytic_walk_first() {
  uvec4 counts = frame_constants.frame.counts;
  uint most = min(kReferenceAnalyticWalkMax, kReferenceAnalyticWalkPerSample * max(push.spp, 1u));
  bool walk = counts.x > counts.z && counts.x - counts.z <= most;
  return walk ? counts.z : 0xffffffffu;
}

// Unshadowed contribution of analytic light i at the shading point and its position y.
vec3 analytic_contribution(Shading sh, uint i, out vec3 y) {
  GpuLight light = scene_light(i);
  y = light_eval_position(light, vec2(0.5), sh.x, frame_constants.frame.scene.x);
  return light_eval_contribution_at(light, y, sh.x, sh.n, sh.ng, sh.v, sh.albedo, sh.roughness,
                                    sh.metallic, sh.specular);
}

// The analytic lights' direct light: n picks with probability t_i / total (t: ReSTIR's target,
// the contribution's luminance), stratified over [0, total) by one offset; each pick adds
// c_i V T total / (n t_i). Unbiased: pick k lands on light i with probability n x the overlap of
// stratum k with i's interval, over total. A light picked k times traces one shadow ray (V is
// the same ray's) and estimates the media's transmittance k times (each pick its own estimate:
// ratio tracking is random, one estimate for all k would multiply its noise by k).
vec3 analytic_picks(Shading sh, vec3 c, vec3 y, float weight, uint k, inout uint rng) {
  if (!vis_visible(sh.x, y)) return vec3(0.0);
  vec3 transmittance = vec3(0.0);
  for (uint j = 0u; j < k; ++j) transmittance += scene_transmittance_between(sh.x, y, rng);
  return c * transmittance * weight;
}

vec3 analytic_lights(Shading sh, uint n, inout uint rng) {
  uint first = analytic_walk_first();
  uint end = frame_constants.frame.counts.x;
  if (first >= end) return vec3(0.0);
  float total = 0.0;
  vec3 y;
  for (uint i = first; i < end; ++i) total += light_eval_target(analytic_contribution(sh, i, y));
  float offset = rng_next_float(rng);
  if (!(total > 0.0)) return vec3(0.0);
  vec3 sum = vec3(0.0);
  float cum = 0.0;
  uint picks = 0u;
  uint last = end;  // the last light with a contribution: rounding's leftover picks go there
  for (uint i = first; i < end && picks < n; ++i) {
    vec3 c = analytic_contribution(sh, i, y);
    float t = light_eval_target(c);
    if (!(t > 0.0)) continue;
    last = i;
    cum += t;
    // Picks k < n with (k + offset) / n < cum / total have landed on this light or earlier ones.
    float until = i + 1u == end ? float(n)
                                : clamp(ceil(cum / total * float(n) - offset), 0.0, float(n));
    if (until > float(picks)) {
      sum += analytic_picks(sh, c, y, total / t, uint(until) - picks, rng);
      picks = uint(until);
    }
  }
  if (picks < n && last < end) {
    vec3 c = analytic_contribution(sh, last, y);
    sum += analytic_picks(sh, c, y, total / light_eval_target(c), n - picks, rng);
  }
  return sum / float(n);
}

// One light sample (environment or alias table), MIS-weighted against BSDF sampling.
vec3 sample_light(Shading sh, inout uint rng) {
  float u_select = rng_next_float(rng);
  float p_env = env_header.env.params.x;
  if (u_select < p_env) {
    vec4 u = vec4(rng_next_vec2(rng), rng_next_vec2(rng));
    vec3 l;
    vec3 le;
    float pdf = p_env * env_sample(env_header.env, u, l, le);
    if (!(pdf > 0.0)) return vec3(0.0);
    vec3 c = light_eval_incident(l, le, 1.0, sh.n, sh.ng, sh.v, sh.albedo, sh.roughness,
                                 sh.metallic, sh.specular);
    if (c == vec3(0.0)) return vec3(0.0);
    float far_t = kDirectionalShadowRadii * frame_constants.frame.scene.x;
    if (!vis_visible(sh.x, sh.x + l * far_t)) return vec3(0.0);
    return c * scene_transmittance(sh.x, l, far_t, rng) *
           (power_heuristic(pdf, bsdf_pdf(sh, l)) / pdf);
  }
  if (frame_constants.frame.counts.x == 0u) return vec3(0.0);
  // Reuse u_select, rescaled to [0,1), for the alias slot.
  float u0 = scene_light_draw_u0(u_select, p_env);
  float u1 = rng_next_float(rng);
  vec2 u_point = rng_next_vec2(rng);
  uint index = scene_light_sample(u0, u1);
  float select = scene_light_strategy_pdf(index, p_env);
  if (index >= analytic_walk_first()) return vec3(0.0);  // analytic_lights() counts it
  GpuLight light = scene_light(index);
  float pdf_point = select * light_eval_point_pdf(light);
  if (!(pdf_point > 0.0)) return vec3(0.0);
  vec3 target = light_eval_position(light, u_point, sh.x, frame_constants.frame.scene.x);
  vec3 c = light_eval_contribution_at(light, target, sh.x, sh.n, sh.ng, sh.v, sh.albedo,
                                      sh.roughness, sh.metallic, sh.specular);
  if (c == vec3(0.0)) return vec3(0.0);
  if (!vis_visible(sh.x, target)) return vec3(0.0);
  c *= scene_transmittance_between(sh.x, target, rng);  // the media along the shadow ray
  // Punctual and directional lights are deltas no BSDF sample can hit (MIS weight 1); a triangle
  // point is weighted against BSDF sampling of the same direction (solid-angle densities).
  float weight = 1.0;
  if (light_kind(light) == kLightTriangle) {
    vec3 to_light = target - sh.x;
    float dist2 = dot(to_light, to_light);
    vec3 l = to_light * inversesqrt(dist2);
    float pdf = select * light_eval_solid_angle_pdf(light, l, dist2);
    weight = power_heuristic(pdf, bsdf_pdf(sh, l));
  }
  return c * (weight / pdf_point);
}

// One BSDF sample: the closest hit's front-facing emission, or the environment on a miss.
vec3 sample_bsdf(Shading sh, inout uint rng) {
  float u_lobe = rng_next_float(rng);
  vec2 u = rng_next_vec2(rng);
  vec3 l = u_lobe < sh.p_specular ? ggx_vndf_sample(sh.n, sh.v, sh.roughness, u)
                                  : cosine_sample_hemisphere(sh.n, u);
  float pdf = bsdf_pdf(sh, l);
  if (!(pdf > 0.0)) return vec3(0.0);
  vec3 f = brdf(sh, l);
  if (f == vec3(0.0)) return vec3(0.0);
  VisHit hit;
  if (vis_trace_closest(bvh_ray_origin(sh.x, sh.ng), l, kVisInfinity, hit)) {
    SurfaceHit s = surface_at(hit);
    vec3 le = emitted(s, scene_materials.m[s.material], l);
    if (le == vec3(0.0)) return vec3(0.0);
    vec3 to_hit = s.position - sh.x;
    float light_pdf =
        s.light != kInvalidLight ? triangle_light_pdf(s.light, dot(to_hit, to_hit), l) : 0.0;
    return f * le * scene_transmittance_between(sh.x, s.position, rng) *
           (power_heuristic(pdf, light_pdf) / pdf);
  }
  if (env_header.env.size.z == 0u) return vec3(0.0);
  vec3 le = env_radiance(env_header.env, l);
  float light_pdf = env_header.env.params.x * env_pdf(env_header.env, l);
  le *= scene_transmittance(sh.x, l, kDirectionalShadowRadii * frame_constants.frame.scene.x, rng);
  return f * le * (power_heuristic(pdf, light_pdf) / pdf);
}

vec3 shade_pixel(uvec2 pixel) {
  FrameConstants fc = frame_constants.frame;
  ivec2 p = ivec2(pixel);
  vec4 position = imageLoad(gbuffer_position, p);
  if (gbuffer_is_sky(position.w)) return env_sky_radiance(fc, pixel);
  vec4 normals = imageLoad(gbuffer_normal, p);
  uvec4 ids = imageLoad(gbuffer_ids, p);
  vec4 emission_metallic = imageLoad(gbuffer_emission_metallic, p);
  GpuMaterial mat = material_at_gbuffer(scene_materials.m[ids.y],
                                        imageLoad(gbuffer_albedo_roughness, p),
                                        emission_metallic.w);
  vec3 result = emission_metallic.rgb;

  Shading sh;
  sh.x = position.xyz;
  sh.v = normalize(fc.camera_position.xyz - sh.x);
  sh.n = oct_decode(normals.xy);   // shading normal, facing the camera
  sh.ng = oct_decode(normals.zw);  // geometric normal, facing the camera
  if (dot(sh.n, sh.ng) < 0.0) sh.n = -sh.n;
  sh.albedo = mat.base_color.rgb;
  sh.roughness = mat.params.x;
  sh.metallic = clamp(mat.params.y, 0.0, 1.0);
  sh.specular = clamp(mat.params.z, 0.0, 1.0);
  float n_dot_v = max(dot(sh.n, sh.v), 0.0);
  float spec = dielectric_specular_albedo(n_dot_v, sh.roughness, sh.specular);
  float w_diffuse = (1.0 - sh.metallic) * (1.0 - spec) * luminance(sh.albedo);
  float w_specular = mix(spec, 1.0, sh.metallic);
  sh.p_specular = w_diffuse + w_specular > 0.0
                      ? clamp(w_specular / (w_diffuse + w_specular), 0.0, 1.0) : 0.0;
  // Keep both lobes reachable unless one is absent.
  if (sh.p_specular > 0.0 && sh.p_specular < 1.0) sh.p_specular = clamp(sh.p_specular, 0.1, 0.9);

  uint rng = frame_rng(pixel, kReferenceRngPass);
  vec3 sum = vec3(0.0);
  for (uint i = 0u; i < push.spp; ++i) {
    vec3 c = sample_light(sh, rng) + sample_bsdf(sh, rng);
    // A non-finite sample counts as black (never NaN/Inf in the output).
    if (is_finite(c.x) && is_finite(c.y) && is_finite(c.z)) sum += max(c, vec3(0.0));
  }
  vec3 analytic = analytic_lights(sh, max(push.spp, 1u), rng);
  if (is_finite(analytic.x) && is_finite(analytic.y) && is_finite(analytic.z)) {
    result += max(analytic, vec3(0.0));
  }
  return result + sum / float(max(push.spp, 1u));
}

void main() {
  uvec2 size = frame_constants.frame.frame.xy;
  uvec2 pixel =
      pixel_tile_origin(gl_WorkGroupID.x, push.tile_stride, 0u, size, gl_WorkGroupSize.xy) +
      gl_LocalInvocationID.xy;
  if (pixel.x >= size.x || pixel.y >= size.y) return;
  vec3 value = shade_pixel(pixel);
  if (!(is_finite(value.x) && is_finite(value.y) && is_finite(value.z))) value = vec3(0.0);
  value = max(value, vec3(0.0));
  radiance.pixels[pixel.y * size.x + pixel.x] = vec4(value, 1.0);
}
