// Participating media, shared by GPU and CPU (CLI.md "Volume units"): the GPU records of a
// volume and its majorant cells, the Henyey-Greenstein phase function, distance sampling in a
// homogeneous medium (exponential, also truncated to a segment), equiangular sampling toward a
// point, their one-sample MIS for scattering distances on a camera ray, and ratio / residual
// ratio tracking transmittance estimators over a segment of constant majorant. The grid
// lookups (bricks, trilinear sampling) are in shared/volume_grid.h.
//
// Conventions
// - Directions are directions of travel. The phase function's cos_theta is the cosine between
//   the direction light travels before and after scattering; g > 0 scatters forward. On a camera
//   ray of direction `ray_dir` (camera -> x) with `to_light` (x -> light):
//   cos_theta = dot(ray_dir, to_light).
// - Ray parameters t are distances along unit world-space directions. A ray carried into a
//   grid's index space with world_to_index keeps its parameter (the direction is not
//   renormalised), so extinctions in 1/m apply to t directly.
// - Tracking reads the medium through one callback: vec3 medium_extinction(uint medium, vec3 p),
//   sigma_t (1/m, per channel) at point p of the ray the caller passed (its own space). GLSL: a
//   shader that calls ratio_tracking / residual_ratio_tracking defines it (declared below). C++:
//   the functions are templates over a medium type whose overload
//   vec3 medium_extinction(const Medium&, uint, vec3) is found by argument-dependent lookup.
#ifndef LANTERN_SHARED_VOLUME_H
#define LANTERN_SHARED_VOLUME_H

#include "shared/common_math.h"
#include "shared/lang.h"
#include "shared/rng.h"

#ifdef __cplusplus
#define LANTERN_MEDIUM_TEMPLATE template <class Medium>
#define LANTERN_MEDIUM_PARAM const Medium &medium_view,
#define LANTERN_MEDIUM medium_view,
#else
#define LANTERN_MEDIUM_TEMPLATE
#define LANTERN_MEDIUM_PARAM
#define LANTERN_MEDIUM
vec3 medium_extinction(uint medium, vec3 p);
#endif

LANTERN_BEGIN_SHARED

// Voxels per cell edge: grids are cut into 8^3-voxel cells (OpenVDB's leaf size), each one cell
// of the majorant grid too. A cell's brick stores 9^3 values: its own 8^3 voxels plus an apron,
// the first layer of its +x, +y and +z neighbours, so every trilinear sample inside the cell
// reads its own brick only (one cell record, eight values, no branch per voxel).
LANTERN_CONST uint kVolumeBrickSize = 8u;
LANTERN_CONST uint kVolumeBrickEdge = 9u;
LANTERN_CONST uint kVolumeBrickVoxels = 729u;
// GpuVolumeCell.brick of a cell whose 9^3 brick voxels are all zero (no values stored).
LANTERN_CONST uint kVolumeEmptyBrick = 0xFFFFFFFFu;
// "No collision": what exponential_sample returns in a medium with zero extinction.
LANTERN_CONST float kVolumeNoCollision = 3.0e38f;
// Tentative collisions one tracking call takes at most. A segment that needs more has a majorant
// optical depth beyond ~4096; the estimate then returns 0 (opaque) rather than the product so
// far, which would skip the rest of the segment and could leak light through a dense voxel the
// walk never reached (a dark bias only where the majorant alone is that deep).
LANTERN_CONST uint kVolumeMaxTrackingSteps = 4096u;

// One volume of the scene (std430). Index space is the grid's: voxel centres at integer
// coordinates, values trilinearly interpolated, zero outside the active region.
struct GpuVolume {
  mat4 world_to_index;  // inverse of index_to_world
  mat4 index_to_world;  // placement * the grid's own index-to-world (affine)
  vec4 scattering;      // xyz: density_scale * scattering (1/m per unit grid value); w: HG g
  vec4 absorption;      // xyz: density_scale * absorption; w: max channel of (scattering +
                        // absorption).xyz, the extinction majorant per unit grid value
  vec4 support_min;     // xyz: index-space box outside which the density is zero (the active
                        //   voxel box grown by one voxel: trilinear reach); w: the mean grid
                        //   value over its non-zero voxels (scattering distances' guide)
  vec4 support_max;     // xyz: the box's upper corner; w: 0
  vec4 cell_origin;     // xyz: index of voxel (0,0,0) of cell (0,0,0), integers; w: 0
  uvec4 cells;          // xyz: cells per axis (x fastest in the cell array); w: first cell
  mat4 motion;          // last frame's world -> this frame's for points of this medium (its
                        //   placement now * inverse(its placement last frame)); identity when still
  mat4 motion_inverse;  // this frame's world -> last frame's
};
LANTERN_STATIC_SIZE(GpuVolume, 352);

// One cell of the majorant grid = one brick of voxels. Cell c covers the index-space box
// [origin + 8c, origin + 8c + 8)^3; every trilinear sample in it reads voxels of
// [origin + 8c, origin + 8c + 8]^3 only, over which max/min_density are taken, so they bound
// the interpolated density in the whole cell.
struct GpuVolumeCell {
  uint brick;         // first value = brick * 729 (9^3, x fastest, then y, z); kVolumeEmptyBrick:
                      // zeros
  float max_density;  // majorant grid value; extinction majorant = max_density * absorption.w
  float min_density;  // lower bound, the control density of residual ratio tracking
  uint pad0;
};
LANTERN_STATIC_SIZE(GpuVolumeCell, 16);

// Push constants of the volume.* passes (lighting/volume/): the image they run over.
struct VolumePush {
  uint width;
  uint height;
  uint samples;  // volume.camera: transmittance + in-scattering samples per pixel (>= 1)
  uint flags;    // kVolumePush*
};
LANTERN_STATIC_SIZE(VolumePush, 16);
// VolumePush.flags: each sample adds a phase-sampled estimate, MIS'd with the light-sampled one
// (the reference; lib/volume_scatter.glsl).
LANTERN_CONST uint kVolumePushPhaseMis = 1u;
LANTERN_CONST uint kVolumeGroupSize = 8u;
// The random stream of volume.camera's estimates (frame_rng's pass).
LANTERN_CONST uint kVolumeRngCamera = 0x564f4cu;

// The volume's guide extinction (1/m): its mean non-zero grid value times the extinction
// majorant per unit value, the rate scattering distances are drawn with.
LANTERN_FUNC float volume_guide_extinction(GpuVolume v) {
  return v.support_min.w * v.absorption.w;
}

// sigma_t (1/m per channel) of volume v where the grid's value is `density`.
LANTERN_FUNC vec3 volume_extinction(GpuVolume v, float density) {
  return density * (vec3(v.scattering) + vec3(v.absorption));
}

// --- Henyey-Greenstein phase function ----------------------------------------------------------

// p(cos_theta) = (1 - g^2) / (4 pi (1 + g^2 - 2 g cos_theta)^(3/2)), per steradian.
LANTERN_FUNC float hg_phase(float cos_theta, float g) {
  float g2 = g * g;
  float denom = 1.0f + g2 - 2.0f * g * clamp(cos_theta, -1.0f, 1.0f);
  return (1.0f - g2) / (4.0f * kPi * denom * sqrt(max(denom, 1e-12f)));
}

// cos_theta distributed by hg_phase, u in [0, 1) (inverse CDF; uniform for |g| < 1e-3).
LANTERN_FUNC float hg_sample_cos_theta(float g, float u) {
  if (abs(g) < 1e-3f) {
    return 1.0f - 2.0f * u;
  }
  float s = (1.0f - g * g) / (1.0f - g + 2.0f * g * u);
  return clamp((1.0f + g * g - s * s) / (2.0f * g), -1.0f, 1.0f);
}

// A direction of travel after scattering, for light travelling along unit `w` before it; its
// pdf (solid angle) is hg_pdf(w, result, g).
LANTERN_FUNC vec3 hg_sample(vec3 w, float g, vec2 u) {
  float cos_theta = hg_sample_cos_theta(g, u.x);
  float sin_theta = sqrt(max(0.0f, 1.0f - cos_theta * cos_theta));
  float phi = kTwoPi * u.y;
  vec3 t;
  vec3 b;
  orthonormal_basis(w, t, b);
  return normalize(to_world(vec3(sin_theta * cos(phi), sin_theta * sin(phi), cos_theta), t, b, w));
}

LANTERN_FUNC float hg_pdf(vec3 w, vec3 w_scattered, float g) {
  return hg_phase(dot(w, w_scattered), g);
}

// Clips [t0, t1] of the ray origin + t dir to the box [lo, hi] (slabs); false when nothing is left.
LANTERN_FUNC bool ray_box_clip(vec3 lo, vec3 hi, vec3 origin, vec3 dir, LANTERN_INOUT(float) t0,
                               LANTERN_INOUT(float) t1) {
  for (int a = 0; a < 3; ++a) {
    if (abs(dir[a]) < 1e-30f) {
      if (origin[a] < lo[a] || origin[a] > hi[a]) {
        return false;
      }
      continue;
    }
    float ta = (lo[a] - origin[a]) / dir[a];
    float tb = (hi[a] - origin[a]) / dir[a];
    t0 = max(t0, min(ta, tb));
    t1 = min(t1, max(ta, tb));
  }
  return t1 > t0;
}

// --- Homogeneous distance sampling --------------------------------------------------------------

// Free-flight distance with density sigma exp(-sigma t), u in [0, 1); kVolumeNoCollision when
// sigma <= 0.
LANTERN_FUNC float exponential_sample(float sigma, float u) {
  if (!(sigma > 0.0f)) {
    return kVolumeNoCollision;
  }
  return -log(1.0f - u) / sigma;
}

LANTERN_FUNC float exponential_pdf(float sigma, float t) {
  return (sigma > 0.0f && t >= 0.0f) ? sigma * exp(-sigma * t) : 0.0f;
}

// Probability of flying past t: exp(-sigma t) (the weight of "no collision before t").
LANTERN_FUNC float exponential_survival(float sigma, float t) {
  return exp(-max(sigma, 0.0f) * max(t, 0.0f));
}

// 1 - exp(-x) for x >= 0, accurate for small x too (GLSL has no expm1).
LANTERN_FUNC float one_minus_exp_neg(float x) {
  return x < 1e-3f ? x * (1.0f - 0.5f * x * (1.0f - x / 3.0f)) : 1.0f - exp(-x);
}

// A distance in [0, t_max] with density proportional to exp(-sigma t) (uniform when sigma is ~0),
// u in [0, 1): scattering points forced inside a segment.
LANTERN_FUNC float exponential_sample_truncated(float sigma, float t_max, float u) {
  float tau = max(sigma, 0.0f) * t_max;
  if (tau < 1e-6f) {
    return u * t_max;
  }
  return min(-log(1.0f - u * one_minus_exp_neg(tau)) / sigma, t_max);
}

LANTERN_FUNC float exponential_pdf_truncated(float sigma, float t_max, float t) {
  if (!(t >= 0.0f && t <= t_max && t_max > 0.0f)) {
    return 0.0f;
  }
  float tau = max(sigma, 0.0f) * t_max;
  if (tau < 1e-6f) {
    return 1.0f / t_max;
  }
  return sigma * exp(-sigma * t) / one_minus_exp_neg(tau);
}

// --- Equiangular sampling (Kulla & Fajardo 2012) ------------------------------------------------
// Distances t in [t_min, t_max] along the ray (origin, unit dir) with density proportional to
// 1 / |x(t) - light|^2: uniform in the angle the segment subtends at the light.

// Foot of the perpendicular from the light (delta, along the ray) and the light's distance to
// the line (at least 1e-6 of the scale, so a light on the line stays finite).
LANTERN_FUNC vec2 equiangular_frame(vec3 origin, vec3 dir, vec3 light) {
  float delta = dot(light - origin, dir);
  float dist = length(light - (origin + delta * dir));
  return vec2(delta, max(dist, 1e-6f * max(1.0f, abs(delta))));
}

// Samples t; `pdf` is its density (1/m). pdf 0 (and t_min) for an empty segment.
LANTERN_FUNC float equiangular_sample(vec3 origin, vec3 dir, vec3 light, float t_min, float t_max,
                                      float u, LANTERN_OUT(float) pdf) {
  vec2 f = equiangular_frame(origin, dir, light);
  float theta_a = atan((t_min - f.x) / f.y);
  float theta_b = atan((t_max - f.x) / f.y);
  if (!(theta_b > theta_a)) {
    pdf = 0.0f;
    return t_min;
  }
  float t = clamp(f.x + f.y * tan(mix(theta_a, theta_b, u)), t_min, t_max);
  float h = t - f.x;
  pdf = f.y / ((theta_b - theta_a) * (f.y * f.y + h * h));
  return t;
}

LANTERN_FUNC float equiangular_pdf(vec3 origin, vec3 dir, vec3 light, float t_min, float t_max,
                                   float t) {
  if (!(t >= t_min && t <= t_max)) {
    return 0.0f;
  }
  vec2 f = equiangular_frame(origin, dir, light);
  float theta_a = atan((t_min - f.x) / f.y);
  float theta_b = atan((t_max - f.x) / f.y);
  if (!(theta_b > theta_a)) {
    return 0.0f;
  }
  float h = t - f.x;
  return f.y / ((theta_b - theta_a) * (f.y * f.y + h * h));
}

// --- Scattering distances on a camera ray (single scattering) --------------------------------
// One distance in the segment [t0, t1] of a ray (origin, unit dir) that crosses a volume, for the
// in-scattering estimate sigma_s(t) T(0, t) L_s(t) / pdf(t). Two techniques:
//   exponential: density proportional to exp(-sigma (t - t0)), sigma the volume's guide
//     extinction (exact importance sampling of the transmittance of a homogeneous medium);
//   equiangular toward the light point `light` (Kulla & Fajardo 2012), when `toward_light`.
// With both, each is picked with probability 1/2 (u.x) and the pdf is their mixture: the
// one-sample balance heuristic, unbiased for any light point chosen independently of t.

LANTERN_FUNC float scatter_distance_pdf(vec3 origin, vec3 dir, float t0, float t1, float sigma,
                                        bool toward_light, vec3 light, float t) {
  float p_exp = exponential_pdf_truncated(sigma, t1 - t0, t - t0);
  if (!toward_light) {
    return p_exp;
  }
  return 0.5f * (p_exp + equiangular_pdf(origin, dir, light, t0, t1, t));
}

LANTERN_FUNC float scatter_distance_sample(vec3 origin, vec3 dir, float t0, float t1, float sigma,
                                           bool toward_light, vec3 light, vec2 u,
                                           LANTERN_OUT(float) pdf) {
  float t;
  if (toward_light && u.x < 0.5f) {
    float p_eq;
    t = equiangular_sample(origin, dir, light, t0, t1, u.y, p_eq);
  } else {
    t = t0 + exponential_sample_truncated(sigma, t1 - t0, u.y);
  }
  t = clamp(t, t0, t1);
  pdf = scatter_distance_pdf(origin, dir, t0, t1, sigma, toward_light, light, t);
  return t;
}

// --- Transmittance estimators over one segment of constant majorant -----------------------------
// Both return an unbiased estimate of exp(-integral of sigma_t over [t0, t1]) per channel along
// origin + t dir, drawing from `rng`; a walker over the majorant grid multiplies the estimates of
// its segments (the exponential's memorylessness makes restarting at a segment boundary exact).
// `roulette` > 0 plays Russian roulette once the estimate's largest channel falls below it
// (unbiased; 0 disables it).

// Russian roulette on a tracked transmittance whose largest channel (in magnitude: residual
// ratio tracking's weights can go negative) fell below `roulette`: it survives with probability
// largest / roulette and is scaled up by its inverse (unbiased); false when it was ended.
LANTERN_FUNC bool tracking_roulette(LANTERN_INOUT(vec3) transmittance, float roulette,
                                    LANTERN_INOUT(uint) rng) {
  float largest = max(abs(transmittance.x), max(abs(transmittance.y), abs(transmittance.z)));
  if (!(largest < roulette)) {
    return true;
  }
  float survive = largest / roulette;
  if (rng_next_float(rng) >= survive) {
    return false;
  }
  transmittance /= survive;
  return true;
}

// Ratio tracking (Cramer 1978; Novak et al. 2014): tentative collisions at rate `majorant`
// (>= every channel of sigma_t on the segment), each multiplying by 1 - sigma_t / majorant.
LANTERN_MEDIUM_TEMPLATE
LANTERN_FUNC vec3 ratio_tracking(LANTERN_MEDIUM_PARAM uint medium, vec3 origin, vec3 dir, float t0,
                                 float t1, float majorant, float roulette,
                                 LANTERN_INOUT(uint) rng) {
  vec3 transmittance = vec3(1.0f);
  if (!(majorant > 0.0f) || !(t1 > t0)) {
    return transmittance;
  }
  float t = t0;
  bool reached_end = false;
  for (uint step = 0u; step < kVolumeMaxTrackingSteps; ++step) {
    t += exponential_sample(majorant, rng_next_float(rng));
    if (t >= t1) {
      reached_end = true;
      break;
    }
    vec3 sigma_t = medium_extinction(LANTERN_MEDIUM medium, origin + t * dir);
    transmittance *= max(vec3(1.0f) - sigma_t / majorant, vec3(0.0f));
    if (!tracking_roulette(transmittance, roulette, rng)) {
      return vec3(0.0f);
    }
  }
  return reached_end ? transmittance : vec3(0.0f);
}

// Residual ratio tracking (Novak et al. 2014): the control extinction `control` (per channel,
// constant on the segment, e.g. min_density * sigma_t per unit density) is integrated
// analytically; only the residual sigma_t - control is tracked, with tentative collisions at
// rate `residual_majorant` (>= every channel of sigma_t - control). Where the medium equals its
// control no collision is drawn at all.
LANTERN_MEDIUM_TEMPLATE
LANTERN_FUNC vec3 residual_ratio_tracking(LANTERN_MEDIUM_PARAM uint medium, vec3 origin, vec3 dir,
                                          float t0, float t1, vec3 control, float residual_majorant,
                                          float roulette, LANTERN_INOUT(uint) rng) {
  if (!(t1 > t0)) {
    return vec3(1.0f);
  }
  vec3 transmittance = exp(-control * (t1 - t0));
  if (!(residual_majorant > 0.0f)) {
    return transmittance;
  }
  float t = t0;
  bool reached_end = false;
  for (uint step = 0u; step < kVolumeMaxTrackingSteps; ++step) {
    t += exponential_sample(residual_majorant, rng_next_float(rng));
    if (t >= t1) {
      reached_end = true;
      break;
    }
    vec3 residual = medium_extinction(LANTERN_MEDIUM medium, origin + t * dir) - control;
    transmittance *= vec3(1.0f) - residual / residual_majorant;
    if (!tracking_roulette(transmittance, roulette, rng)) {
      return vec3(0.0f);
    }
  }
  return reached_end ? transmittance : vec3(0.0f);
}

LANTERN_END_SHARED

#endif
