// What a traced ray found when it is looking for light (the reference's BSDF rays, the media's
// phase rays): the surface record of a closest hit, the radiance a front-facing emitter sends
// back along the ray, and the densities light sampling has for the same light, for MIS (power
// heuristic, Veach 1995). Needs lib/scene_buffers.glsl first.
#ifndef LANTERN_LIB_EMITTER_HIT_GLSL
#define LANTERN_LIB_EMITTER_HIT_GLSL

#include "shared/light_eval.h"

struct SurfaceHit {
  vec3 position;
  vec3 geometric_normal;  // front-face normal (winding, mirrored by a negative determinant)
  vec3 shading_normal;    // interpolated vertex normal (may be zero: then the geometric one)
  uint material;
  uint light;             // this triangle's light index, or kInvalidLight
};

SurfaceHit surface_at(VisHit hit) {
  GpuInstance inst = scene_instances.i[hit.instance];
  uint base = inst.geometry.y + 3u * hit.primitive;
  uint first_vertex = inst.geometry.w;
  GpuVertex v0 = scene_vertices.v[first_vertex + scene_indices.i[base]];
  GpuVertex v1 = scene_vertices.v[first_vertex + scene_indices.i[base + 1u]];
  GpuVertex v2 = scene_vertices.v[first_vertex + scene_indices.i[base + 2u]];
  mat3 linear = mat3(inst.object_to_world);
  vec3 p0 = (inst.object_to_world * vec4(v0.position_u.xyz, 1.0)).xyz;
  vec3 e1 = linear * (v1.position_u.xyz - v0.position_u.xyz);
  vec3 e2 = linear * (v2.position_u.xyz - v0.position_u.xyz);
  SurfaceHit s;
  s.position = p0 + hit.u * e1 + hit.v * e2;
  vec3 ng = cross(e1, e2);
  if (determinant(linear) < 0.0) ng = -ng;
  s.geometric_normal = normalize(ng);
  vec3 n_object = (1.0 - hit.u - hit.v) * v0.normal_v.xyz + hit.u * v1.normal_v.xyz +
                  hit.v * v2.normal_v.xyz;
  vec3 n_world = transpose(mat3(inst.world_to_object)) * n_object;
  s.shading_normal = dot(n_world, n_world) > 0.0 ? normalize(n_world) : s.geometric_normal;
  s.material = inst.geometry.x;
  s.light = inst.bvh.y == kInvalidLight ? kInvalidLight : inst.bvh.y + hit.primitive;
  return s;
}

// Radiance a front-facing emitter sends towards -dir: its light record when it has one (the
// same value light sampling uses), else the material's emission.
vec3 emitted(SurfaceHit s, GpuMaterial mat, vec3 dir) {
  if (dot(s.geometric_normal, dir) >= 0.0) return vec3(0.0);
  return s.light != kInvalidLight ? light_eval_radiance(scene_light(s.light), s.position)
                                   : mat.emission.rgb;
}

// Probability that light sampling produces direction l towards a point on triangle light `index`
// at squared distance dist2 (both selection steps), as a solid-angle density.
float triangle_light_pdf(uint index, float dist2, vec3 l) {
  if (frame_constants.frame.counts.x == 0u) return 0.0;
  float select = (1.0 - env_header.env.params.x) * scene_light_selection_pdf(index);
  return select * light_eval_solid_angle_pdf(scene_light(index), l, dist2);
}

float power_heuristic(float a, float b) {
  float a2 = a * a;
  float b2 = b * b;
  return a2 + b2 > 0.0 ? finite_positive_or_zero(a2 / (a2 + b2)) : 0.0;
}

#endif
