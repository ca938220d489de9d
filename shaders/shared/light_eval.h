// One light sample y = (light, uv) seen from a surface point x, shared by the ReSTIR passes and
// CPU tests: the point on the light, the unshadowed contribution f(x, l) Le G, and the density of
// drawing y by light sampling. The measure is the light's own: area for triangles (uv -> uniform
// point), counting for point/spot/directional lights. So a sample means the same point at every
// pixel and every frame, and reservoirs move between pixels without a Jacobian.
//
//   contribution c(x, y) = f(v, l) cos(n, l) * Le * G,  G = cos_light / d^2 (triangles),
//                          falloff (point/spot), 1 (directional)
//   an estimate of the direct light is c(x, y) V(x, y) / p(y); ReSTIR's target is luminance(c).
// Every integrator (baseline, reference, the restir.* passes) evaluates lights through these
// functions: one owner for range, cone, falloff and the directional shadow distance.
#ifndef LANTERN_SHARED_LIGHT_EVAL_H
#define LANTERN_SHARED_LIGHT_EVAL_H

#include "shared/brdf.h"
#include "shared/color.h"
#include "shared/common_math.h"
#include "shared/lang.h"
#include "shared/lights.h"
#include "shared/sampling.h"
#include "shared/volume.h"

LANTERN_BEGIN_SHARED

// Shadow rays to directional lights and environment directions end this many scene radii away
// (anything that can block them lies inside the scene's bounding sphere).
LANTERN_CONST float kDirectionalShadowRadii = 4.0f;

// The point the sample lights x from (for the shadow ray). uv in [0,1]^2.
LANTERN_FUNC vec3 light_eval_position(GpuLight light, vec2 uv, vec3 x, float scene_radius) {
  uint kind = light_kind(light);
  if (kind == kLightTriangle) {
    vec3 p0 = vec3(light.p0);
    return triangle_point(p0, p0 + vec3(light.p1), p0 + vec3(light.p2),
                          triangle_sample_barycentrics(uv));
  }
  if (kind == kLightDirectional) {
    return x + directional_light_to_light(vec3(light.p1)) * (kDirectionalShadowRadii * scene_radius);
  }
  return vec3(light.p0);
}

// Density of y = (light, uv) given the light was chosen: 1 / area for triangles (0 for a
// degenerate one), 1 for punctual and directional lights. Multiply by the selection pdf.
LANTERN_FUNC float light_eval_point_pdf(GpuLight light) {
  if (light_kind(light) != kLightTriangle) {
    return 1.0f;
  }
  vec3 p0 = vec3(light.p0);
  return safe_ratio(1.0f, triangle_area(p0, p0 + vec3(light.p1), p0 + vec3(light.p2)));
}

// Cosine at the light and squared distance of a triangle light point y seen from x: the factor
// cos_light / d^2 that turns a solid-angle density into an area density. Zero behind the
// one-sided triangle and for a degenerate one.
LANTERN_FUNC float light_eval_triangle_geometry(GpuLight light, vec3 l, float dist2) {
  vec3 light_normal = cross(vec3(light.p1), vec3(light.p2));
  float len2 = dot(light_normal, light_normal);
  float cos_light = len2 > 0.0f ? -dot(light_normal, l) * inversesqrt(len2) : 0.0f;
  return cos_light > 0.0f ? safe_ratio(cos_light, dist2) : 0.0f;
}

// Solid-angle density at x of light sampling landing on triangle light point y in unit direction
// l at squared distance dist2, given the light was chosen (multiply by the selection pdf):
// point density / (cos_light / d^2). Zero for punctual and directional lights (deltas: no other
// strategy reaches them) and behind the triangle.
LANTERN_FUNC float light_eval_solid_angle_pdf(GpuLight light, vec3 l, float dist2) {
  if (light_kind(light) != kLightTriangle) {
    return 0.0f;
  }
  float geometry = light_eval_triangle_geometry(light, l, dist2);
  return geometry > 0.0f ? safe_ratio(light_eval_point_pdf(light), geometry) : 0.0f;
}

// The geometry term at x of the light point y (light_eval_position's) and the unit direction l
// towards it: cos_light / d^2 for triangles; 1/d^2 with the KHR_lights_punctual range window
// (p2.w; 0 = none) for point lights, times the cone for spots; 1 for directional lights (y not
// used). Zero when x coincides with the light.
LANTERN_FUNC float light_eval_geometry(GpuLight light, vec3 y, vec3 x, LANTERN_OUT(vec3) l) {
  uint kind = light_kind(light);
  if (kind == kLightDirectional) {
    l = directional_light_to_light(vec3(light.p1));
    return 1.0f;
  }
  vec3 to_light = y - x;
  float dist2 = dot(to_light, to_light);
  if (!(dist2 > 0.0f)) {
    l = vec3(0.0f, 0.0f, 1.0f);
    return 0.0f;
  }
  l = to_light * inversesqrt(dist2);
  if (kind == kLightTriangle) {
    return light_eval_triangle_geometry(light, l, dist2);
  }
  float geometry = punctual_distance_falloff(dist2, light.p2.w);
  if (kind == kLightSpot) {
    vec3 axis = vec3(light.p1);
    float axis_len2 = dot(axis, axis);
    float cos_theta = axis_len2 > 0.0f ? dot(axis, -l) * inversesqrt(axis_len2) : -1.0f;
    geometry *= spot_cone_falloff(cos_theta, light.p2.x, light.p2.y);
  }
  return geometry;
}

// Unshadowed contribution of radiance `radiance` arriving along unit direction l, times the
// geometry term `geometry` (1 for a direction's radiance): f(v, l) cos(n, l) radiance geometry. n:
// shading normal, ng: geometric normal, both on the viewer's side; v: unit direction to the
// viewer. Zero below the geometric normal and for non-finite inputs. Every light kind ends here,
// the environment map included.
LANTERN_FUNC vec3 light_eval_incident(vec3 l, vec3 radiance, float geometry, vec3 n, vec3 ng,
                                      vec3 v, vec3 albedo, float roughness, float metallic,
                                      float specular) {
  if (dot(ng, l) <= 0.0f) {
    return vec3(0.0f);
  }
  vec3 c = brdf_eval(n, v, l, albedo, roughness, metallic, specular) * radiance * geometry;
  bool finite = is_finite(c.x) && is_finite(c.y) && is_finite(c.z);
  return finite ? max(c, vec3(0.0f)) : vec3(0.0f);
}

// Barycentrics (b1, b2) of the point y on triangle light `light` (least squares in its plane).
LANTERN_FUNC vec2 light_eval_triangle_barycentrics(GpuLight light, vec3 y) {
  vec3 e1 = vec3(light.p1);
  vec3 e2 = vec3(light.p2);
  vec3 w = y - vec3(light.p0);
  float d00 = dot(e1, e1);
  float d01 = dot(e1, e2);
  float d11 = dot(e2, e2);
  float d20 = dot(w, e1);
  float d21 = dot(w, e2);
  float denom = d00 * d11 - d01 * d01;
  if (!(denom > 0.0f)) {
    return vec2(1.0f / 3.0f, 1.0f / 3.0f);
  }
  return vec2((d11 * d20 - d01 * d21) / denom, (d00 * d21 - d01 * d20) / denom);
}

// The emissive texture factor of textured triangle light record `record` at barycentrics
// (b1, b2). GLSL: declared here, defined by lib/scene_buffers.glsl (every frame pass includes
// it; a shader that calls light evaluation without it fails to link). C++: the CPU callers (unit
// tests of the light math) have no textures: 1.
#ifdef __cplusplus
inline vec3 scene_textured_emitter_radiance(uint, float, float) { return vec3(1.0f); }
#else
vec3 scene_textured_emitter_radiance(uint record, float b1, float b2);
#endif

// Emitted radiance of `light` towards its front at its point y: radiance.rgb, times the emissive
// texture at y for a textured triangle light (radiance.w = uintBitsToFloat(record + 1), see
// shared/textures.h GpuTexturedEmitter).
LANTERN_FUNC vec3 light_eval_radiance(GpuLight light, vec3 y) {
  vec3 radiance = vec3(light.radiance);
  uint record = floatBitsToUint(light.radiance.w);
  if (record != 0u && light_kind(light) == kLightTriangle) {
    vec2 b = light_eval_triangle_barycentrics(light, y);
    radiance *= scene_textured_emitter_radiance(record - 1u, b.x, b.y);
  }
  return radiance;
}

// Unshadowed contribution c(x, y) of the light point y (light_eval_position's; see the header):
// zero below either normal, behind a one-sided triangle, outside a spot cone or a punctual range,
// and for non-finite inputs. Arguments as light_eval_incident. For a caller that also traces the
// shadow ray towards y.
LANTERN_FUNC vec3 light_eval_contribution_at(GpuLight light, vec3 y, vec3 x, vec3 n, vec3 ng,
                                             vec3 v, vec3 albedo, float roughness, float metallic,
                                             float specular) {
  vec3 l;
  float geometry = light_eval_geometry(light, y, x, l);
  if (!(geometry > 0.0f)) {
    return vec3(0.0f);
  }
  return light_eval_incident(l, light_eval_radiance(light, y), geometry, n, ng, v, albedo,
                             roughness, metallic, specular);
}

// The same for sample (light, uv).
LANTERN_FUNC vec3 light_eval_contribution(GpuLight light, vec2 uv, vec3 x, vec3 n, vec3 ng, vec3 v,
                                          vec3 albedo, float roughness, float metallic,
                                          float specular, float scene_radius) {
  return light_eval_contribution_at(light, light_eval_position(light, uv, x, scene_radius), x, n,
                                    ng, v, albedo, roughness, metallic, specular);
}

// --- Media: the same light seen from a scattering point x (shared/volume.h conventions) -------
// The phase function takes the place of f cos: a camera ray of unit direction ray_dir scatters
// towards the light with Henyey-Greenstein anisotropy g. Multiply by sigma_s(x) for the
// in-scattered radiance per metre.

// phase(dot(ray_dir, l)) * radiance * geometry; zero for non-finite inputs.
LANTERN_FUNC vec3 light_eval_scattered_incident(vec3 l, vec3 radiance, float geometry,
                                                vec3 ray_dir, float g) {
  vec3 c = hg_phase(dot(ray_dir, l), g) * radiance * geometry;
  bool finite = is_finite(c.x) && is_finite(c.y) && is_finite(c.z);
  return finite ? max(c, vec3(0.0f)) : vec3(0.0f);
}

// Unshadowed contribution of the light point y (light_eval_position's) at medium point x: zero
// behind a one-sided triangle, outside a spot cone or a punctual range, and where x is on y.
LANTERN_FUNC vec3 light_eval_scattered_at(GpuLight light, vec3 y, vec3 x, vec3 ray_dir,
                                          float g) {
  vec3 l;
  float geometry = light_eval_geometry(light, y, x, l);
  if (!(geometry > 0.0f)) {
    return vec3(0.0f);
  }
  return light_eval_scattered_incident(l, light_eval_radiance(light, y), geometry, ray_dir, g);
}

// ReSTIR's target function p̂(y) at x: luminance of the unshadowed contribution, guarded.
LANTERN_FUNC float light_eval_target(vec3 contribution) {
  return finite_positive_or_zero(luminance(contribution));
}

// Inverse of triangle_sample_barycentrics: the uv that lands on barycentrics (b0, b1, b2), for a
// light hit by a BSDF-sampled ray. Clamped to [0,1]^2.
LANTERN_FUNC vec2 triangle_barycentrics_to_uv(float b1, float b2) {
  float one_minus_b0 = clamp(b1 + b2, 0.0f, 1.0f);
  float u = one_minus_b0 * one_minus_b0;
  float v = one_minus_b0 > 0.0f ? clamp(b1 / one_minus_b0, 0.0f, 1.0f) : 0.0f;
  return vec2(u, v);
}

LANTERN_END_SHARED

#endif
