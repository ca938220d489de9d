// Geometry of light sampling shared by GPU and CPU: uniform points on triangles with their area
// pdf and its solid-angle form, and the falloff of punctual lights per KHR_lights_punctual
// (inverse square, optional range window, spot cone).
#ifndef LANTERN_SHARED_SAMPLING_H
#define LANTERN_SHARED_SAMPLING_H

#include "shared/common_math.h"
#include "shared/lang.h"

LANTERN_BEGIN_SHARED

// Barycentrics (b0, b1, b2) of a uniformly distributed point on a triangle, u in [0,1)^2
// (square-root warp; point = b0 p0 + b1 p1 + b2 p2).
LANTERN_FUNC vec3 triangle_sample_barycentrics(vec2 u) {
  float su = sqrt(u.x);
  float b0 = 1.0f - su;
  float b1 = u.y * su;
  return vec3(b0, b1, 1.0f - b0 - b1);
}

LANTERN_FUNC vec3 triangle_point(vec3 p0, vec3 p1, vec3 p2, vec3 bary) {
  return bary.x * p0 + bary.y * p1 + bary.z * p2;
}

LANTERN_FUNC float triangle_area(vec3 p0, vec3 p1, vec3 p2) {
  return 0.5f * length(cross(p1 - p0, p2 - p0));
}

// Area pdf (1/m^2) -> solid-angle pdf (1/sr) seen from a point at squared distance dist2, where
// cos_light is the cosine between the light's normal and the direction back to the receiver.
// Zero for back-facing or degenerate configurations.
LANTERN_FUNC float area_to_solid_angle_pdf(float pdf_area, float dist2, float cos_light) {
  return cos_light > 0.0f ? safe_ratio(pdf_area * dist2, cos_light) : 0.0f;
}

// Solid-angle pdf of a uniform point on a triangle of the given area.
LANTERN_FUNC float triangle_solid_angle_pdf(float area, float dist2, float cos_light) {
  return area_to_solid_angle_pdf(safe_ratio(1.0f, area), dist2, cos_light);
}

// Punctual light falloff with distance: 1/d^2, times glTF's recommended smooth range window
// clamp(1 - (d/range)^4, 0, 1)^2 when range > 0 (range <= 0: no range, pure inverse square).
LANTERN_FUNC float punctual_distance_falloff(float dist2, float range) {
  float inv_square = safe_ratio(1.0f, dist2);
  if (range <= 0.0f) {
    return inv_square;
  }
  float ratio2 = dist2 / (range * range);
  float window = clamp(1.0f - ratio2 * ratio2, 0.0f, 1.0f);
  return inv_square * window * window;
}

// Spot cone attenuation exactly as the KHR_lights_punctual specification gives it:
// scale = 1 / max(0.001, cos_inner - cos_outer), offset = -cos_outer * scale,
// a = clamp(cos_theta * scale + offset, 0, 1), attenuation = a^2. cos_theta is the cosine
// between the spot direction and the direction from the light to the receiver.
LANTERN_FUNC float spot_cone_falloff(float cos_theta, float cos_outer, float cos_inner) {
  float scale = 1.0f / max(0.001f, cos_inner - cos_outer);
  float offset = -cos_outer * scale;
  float a = clamp(cos_theta * scale + offset, 0.0f, 1.0f);
  return a * a;
}

// Direction from a receiver towards a directional light travelling along `travel_dir`.
LANTERN_FUNC vec3 directional_light_to_light(vec3 travel_dir) {
  return -normalize(travel_dir);
}

LANTERN_END_SHARED

#endif
