// The surface BRDF shared by shading, ReSTIR target functions and CPU tests: glTF
// metallic-roughness with KHR_materials_specular (white specular colour, ior 1.5), i.e. Lambert
// diffuse + GGX specular with height-correlated Smith G2 and Schlick Fresnel. Plus importance
// sampling: GGX visible normals (Heitz 2018) and cosine-weighted Lambert, with their pdfs.
//
// Energy conservation: the dielectric layer reflects F_s(v.h) = s * Schlick(F0 = 0.04, v.h)
// through the GGX lobe (s = KHR_materials_specular factor); the Lambert base receives what the
// layer does not reflect on the way in and on the way out: it is weighted by
// (1 - s E(n.v)) (1 - s E(n.l)), E = an upper estimate of the specular lobe's directional
// albedo (dielectric_specular_albedo). Symmetric in v and l, so reciprocal; s = 0 gives pure
// Lambert. Two rejected forms, measured by the white-furnace test: glTF's 1 - F(v.h) reflects up
// to 1.54x the incident energy at grazing view; 1 - F(n.v) per side loses up to 60% on rough
// surfaces at grazing view. Metals are GGX with Schlick F0 = base colour and no diffuse. Directions
// n, v (towards the viewer), l (towards the light) are unit vectors in world space.
#ifndef LANTERN_SHARED_BRDF_H
#define LANTERN_SHARED_BRDF_H

#include "shared/common_math.h"
#include "shared/lang.h"

LANTERN_BEGIN_SHARED

// alpha floor: keeps D finite (1 / (pi alpha^2) <= 3.2e5) for perfectly smooth inputs.
LANTERN_CONST float kMinGgxAlpha = 1e-3f;
// Normal-incidence reflectance of a dielectric with ior 1.5: ((1 - 1.5) / (1 + 1.5))^2.
LANTERN_CONST float kDielectricF0 = 0.04f;

// glTF: alpha = perceptual roughness squared.
LANTERN_FUNC float ggx_alpha(float roughness) {
  float r = clamp(roughness, 0.0f, 1.0f);
  return max(r * r, kMinGgxAlpha);
}

// GGX normal distribution D(h) for cos(n, h) and alpha^2.
LANTERN_FUNC float ggx_d(float n_dot_h, float alpha2) {
  if (n_dot_h <= 0.0f) {
    return 0.0f;
  }
  float d = n_dot_h * n_dot_h * (alpha2 - 1.0f) + 1.0f;
  return alpha2 / (kPi * d * d);
}

// Smith G1 of GGX for one direction at cos(n, w).
LANTERN_FUNC float ggx_smith_g1(float n_dot_w, float alpha2) {
  if (n_dot_w <= 0.0f) {
    return 0.0f;
  }
  return 2.0f * n_dot_w / (n_dot_w + sqrt(alpha2 + (1.0f - alpha2) * n_dot_w * n_dot_w));
}

// Height-correlated Smith G2 folded with the specular denominator:
// V = G2(v, l) / (4 n.v n.l), so the specular lobe is D * V * F.
LANTERN_FUNC float ggx_smith_v_height_correlated(float n_dot_v, float n_dot_l, float alpha2) {
  float lambda_v = n_dot_l * sqrt(n_dot_v * n_dot_v * (1.0f - alpha2) + alpha2);
  float lambda_l = n_dot_v * sqrt(n_dot_l * n_dot_l * (1.0f - alpha2) + alpha2);
  return 0.5f / (lambda_v + lambda_l);
}

// Schlick's (1 - cos)^5.
LANTERN_FUNC float schlick_weight(float cos_theta) {
  float m = clamp(1.0f - cos_theta, 0.0f, 1.0f);
  float m2 = m * m;
  return m2 * m2 * m;
}

// Fresnel reflectance of the dielectric layer at cos_theta, scaled by the specular factor s.
LANTERN_FUNC float dielectric_fresnel(float cos_theta, float s) {
  return s * (kDielectricF0 + (1.0f - kDielectricF0) * schlick_weight(cos_theta));
}

// Upper estimate of the directional albedo of the dielectric GGX lobe seen from cos(n, w), scaled
// by s: Schlick's F0 + (1 - F0)(1 - cos)^5 with the grazing term damped by roughness,
// g(r) = max(1 / (1 + 60 r^6.2), 0.04). Fitted from above to this lobe's albedo measured by Monte
// Carlo (within a few % where it matters; smooth surfaces give Schlick, rough ones lose the
// grazing peak they do not have).
LANTERN_FUNC float dielectric_specular_albedo(float n_dot_w, float roughness, float s) {
  float r = clamp(roughness, 0.0f, 1.0f);
  float grazing = max(1.0f / (1.0f + 60.0f * pow(r, 6.2f)), 0.04f);
  float w = schlick_weight(n_dot_w);
  return s * (kDielectricF0 + (1.0f - kDielectricF0) * w * grazing);
}

// BRDF times the cosine at the light: f(v, l) * max(n.l, 0), in 1/sr. Zero when v or l is below
// the surface. albedo = base colour, specular = KHR_materials_specular factor (0: pure Lambert).
LANTERN_FUNC vec3 brdf_eval(vec3 n, vec3 v, vec3 l, vec3 albedo, float roughness, float metallic,
                            float specular) {
  float n_dot_l = dot(n, l);
  float n_dot_v = dot(n, v);
  if (n_dot_l <= 0.0f || n_dot_v <= 0.0f) {
    return vec3(0.0f);
  }
  vec3 h = normalize(v + l);
  float n_dot_h = dot(n, h);
  float v_dot_h = max(dot(v, h), 0.0f);
  float alpha = ggx_alpha(roughness);
  float alpha2 = alpha * alpha;
  float lobe = ggx_d(n_dot_h, alpha2) * ggx_smith_v_height_correlated(n_dot_v, n_dot_l, alpha2);
  float w = schlick_weight(v_dot_h);
  float s = clamp(specular, 0.0f, 1.0f);
  float diffuse_in = 1.0f - dielectric_specular_albedo(n_dot_v, roughness, s);
  float diffuse_out = 1.0f - dielectric_specular_albedo(n_dot_l, roughness, s);
  vec3 dielectric =
      (diffuse_in * diffuse_out * kInvPi) * albedo + vec3(dielectric_fresnel(v_dot_h, s) * lobe);
  vec3 metal = (albedo + (vec3(1.0f) - albedo) * w) * lobe;
  float m = clamp(metallic, 0.0f, 1.0f);
  return mix(dielectric, metal, m) * n_dot_l;
}

// How glossy a surface is, as BSDF sampling sees it: the GGX lobe's share of the mixture that
// ReSTIR's BSDF candidates draw from (the rest cosine-weighted), max(metallic, specular factor x
// (1 - roughness) / 2), in [0, 1]: 1 for metals, at most 0.5 for dielectrics. Also what
// `restir.bsdf_min_gloss` compares (RestirSettings).
LANTERN_FUNC float brdf_gloss(float roughness, float metallic, float specular) {
  return clamp(max(metallic, 0.5f * specular * (1.0f - roughness)), 0.0f, 1.0f);
}

// GGX visible-normal sample (Heitz 2018, "Sampling the GGX Distribution of Visible Normals"),
// reflected into a direction l. l may point below the surface (then brdf_eval is 0). u in [0,1)^2.
LANTERN_FUNC vec3 ggx_vndf_sample(vec3 n, vec3 v, float roughness, vec2 u) {
  vec3 t;
  vec3 b;
  orthonormal_basis(n, t, b);
  float alpha = ggx_alpha(roughness);
  vec3 v_local = vec3(dot(v, t), dot(v, b), max(dot(v, n), 1e-6f));
  vec3 vh = normalize(vec3(alpha * v_local.x, alpha * v_local.y, v_local.z));
  float len2 = vh.x * vh.x + vh.y * vh.y;
  vec3 t1 = len2 > 0.0f ? vec3(-vh.y, vh.x, 0.0f) * inversesqrt(len2) : vec3(1.0f, 0.0f, 0.0f);
  vec3 t2 = cross(vh, t1);
  float r = sqrt(u.x);
  float phi = kTwoPi * u.y;
  float p1 = r * cos(phi);
  float p2 = r * sin(phi);
  float s = 0.5f * (1.0f + vh.z);
  p2 = (1.0f - s) * sqrt(max(1.0f - p1 * p1, 0.0f)) + s * p2;
  vec3 nh = p1 * t1 + p2 * t2 + sqrt(max(1.0f - p1 * p1 - p2 * p2, 0.0f)) * vh;
  vec3 h_local = normalize(vec3(alpha * nh.x, alpha * nh.y, max(nh.z, 0.0f)));
  vec3 h = to_world(h_local, t, b, n);
  return reflect(-v, h);
}

// Solid-angle pdf of ggx_vndf_sample producing l: G1(v) D(h) / (4 n.v), over the whole sphere.
LANTERN_FUNC float ggx_vndf_pdf(vec3 n, vec3 v, vec3 l, float roughness) {
  float n_dot_v = dot(n, v);
  vec3 sum = v + l;
  float len2 = dot(sum, sum);
  if (n_dot_v <= 0.0f || len2 <= 0.0f) {
    return 0.0f;
  }
  vec3 h = sum * inversesqrt(len2);
  float alpha = ggx_alpha(roughness);
  float alpha2 = alpha * alpha;
  return ggx_smith_g1(n_dot_v, alpha2) * ggx_d(dot(n, h), alpha2) / (4.0f * n_dot_v);
}

// Cosine-weighted hemisphere direction around n (Lambert importance sampling). u in [0,1)^2.
LANTERN_FUNC vec3 cosine_sample_hemisphere(vec3 n, vec2 u) {
  vec3 t;
  vec3 b;
  orthonormal_basis(n, t, b);
  float r = sqrt(u.x);
  float phi = kTwoPi * u.y;
  vec3 local = vec3(r * cos(phi), r * sin(phi), sqrt(max(1.0f - u.x, 0.0f)));
  return to_world(local, t, b, n);
}

// Solid-angle pdf of cosine_sample_hemisphere: max(n.l, 0) / pi.
LANTERN_FUNC float cosine_hemisphere_pdf(vec3 n, vec3 l) {
  return max(dot(n, l), 0.0f) * kInvPi;
}

LANTERN_END_SHARED

#endif
