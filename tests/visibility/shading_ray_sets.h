// Shadow-ray sets made like the integrators' (visibility_bench's study of why a restir.shade ray
// costs more than a baseline one): from every CPU primary hit, with the hit's material and facing
// geometric normal (as the shading normal too), a light point drawn
//   baseline: from the power alias table and a uniform point on the light, as integrators.baseline;
//   ris-M:    by resampled importance sampling over M such candidates with target p̂ = luminance of
//             the unshadowed contribution (shared/light_eval.h), as restir.initial (balanced: 8
//             light candidates); temporal and spatial reuse push the pick further towards large
//             p̂, which a larger M stands in for (the M cap of balanced is 20 x 8 = 160).
// Like the integrators, a pick with zero unshadowed contribution (light below the surface or
// facing away) traces no ray. Emitters only: the environment's share is not drawn. Also
// closest-hit rays like restir.initial's BSDF candidates (bsdf_rays).
#pragma once

#include <algorithm>
#include <cstdint>
#include <glm/glm.hpp>
#include <random>
#include <span>
#include <utility>
#include <vector>

#include "engine/scene/level.h"
#include "lighting/scene/scene_data.h"
#include "shared/brdf.h"
#include "shared/bvh.h"
#include "shared/light_eval.h"

namespace lantern::lighting::test {

// A CPU primary hit as the shading passes see it: the point, the geometric normal facing the
// ray, the direction back to the camera and the material.
struct SurfaceHit {
  glm::vec3 x;
  glm::vec3 ng;
  glm::vec3 view;
  const gpu::GpuMaterial* material;
};

inline SurfaceHit surface_hit(const Level& level, const SceneData& data, const gpu::BvhRay& ray,
                              const gpu::BvhHit& hit) {
  const Instance& inst = level.instances[hit.instance];
  const Mesh& mesh = level.meshes[inst.mesh];
  glm::vec3 v[3];
  for (int k = 0; k < 3; ++k)
    v[k] = glm::vec3(inst.world *
                     glm::vec4(mesh.positions[mesh.indices[3 * hit.primitive + k]], 1.0f));
  const glm::vec3 dir(ray.direction);
  glm::vec3 ng = glm::normalize(glm::cross(v[1] - v[0], v[2] - v[0]));
  if (glm::dot(ng, dir) > 0.0f) ng = -ng;
  return {glm::vec3(ray.origin) + hit.t * dir, ng, -glm::normalize(dir),
          &data.materials[data.instances[hit.instance].geometry.x]};
}

// Closest-hit rays like restir.initial's BSDF candidates: from every CPU primary hit, offset off
// the surface (bvh_ray_origin), one cosine-distributed direction about the facing geometric
// normal, unbounded.
inline std::vector<gpu::BvhRay> bsdf_rays(const Level& level, const SceneData& data,
                                          std::span<const gpu::BvhRay> primary,
                                          std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<gpu::BvhRay> rays;
  for (const gpu::BvhRay& ray : primary) {
    gpu::BvhHit hit;
    if (!data.bvh.trace_closest(ray, hit)) continue;
    const SurfaceHit s = surface_hit(level, data, ray, hit);
    const glm::vec3 l = gpu::cosine_sample_hemisphere(s.ng, glm::vec2(u(rng), u(rng)));
    rays.push_back(gpu::bvh_make_ray(gpu::bvh_ray_origin(s.x, s.ng), l, 0.0f, gpu::kBvhMiss));
  }
  return rays;
}

struct ShadingRaySet {
  std::vector<gpu::BvhRay> rays;      // origin -> light point segments (probe mode 1)
  std::size_t surface_points = 0;     // primary hits
  std::size_t zero_contribution = 0;  // picks that light nothing: no ray
};

// candidates = 0: the baseline's single power-sampled pick; otherwise RIS over that many.
inline ShadingRaySet shading_shadow_rays(const Level& level, const SceneData& data,
                                         std::span<const gpu::BvhRay> primary,
                                         std::uint32_t candidates, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const auto& lights = data.lights.lights();
  const float radius = data.scene_radius();
  ShadingRaySet set;
  if (lights.empty()) return set;
  for (const gpu::BvhRay& ray : primary) {
    gpu::BvhHit hit;
    if (!data.bvh.trace_closest(ray, hit)) continue;
    ++set.surface_points;
    const SurfaceHit surface = surface_hit(level, data, ray, hit);
    const glm::vec3 x = surface.x;
    const glm::vec3 ng = surface.ng;
    const glm::vec3 view = surface.view;
    const gpu::GpuMaterial& mat = *surface.material;
    const auto contribution = [&](std::uint32_t index, glm::vec3 y) {
      return gpu::light_eval_contribution_at(lights[index], y, x, ng, ng, view,
                                             glm::vec3(mat.base_color), mat.params.x, mat.params.y,
                                             mat.params.z);
    };
    const auto draw = [&](std::uint32_t& index, glm::vec3& y) {
      const float u0 = u(rng), u1 = u(rng);
      index = data.lights.sample(u0, u1);
      y = gpu::light_eval_position(lights[index], glm::vec2(u(rng), u(rng)), x, radius);
    };
    std::uint32_t pick = 0;
    glm::vec3 y(0.0f), c(0.0f);
    if (candidates == 0) {
      draw(pick, y);
      c = contribution(pick, y);
    } else {
      float weight_sum = 0.0f;
      for (std::uint32_t i = 0; i < candidates; ++i) {
        std::uint32_t index = 0;
        glm::vec3 yi(0.0f);
        draw(index, yi);
        const glm::vec3 ci = contribution(index, yi);
        const float p = data.lights.selection_pdf(index) * gpu::light_eval_point_pdf(lights[index]);
        const float w = p > 0.0f ? gpu::light_eval_target(ci) / p : 0.0f;
        weight_sum += w;
        if (w > 0.0f && u(rng) * weight_sum < w) pick = index, y = yi, c = ci;
      }
    }
    if (c == glm::vec3(0.0f)) {
      ++set.zero_contribution;
      continue;
    }
    set.rays.push_back(gpu::bvh_make_ray(x, y - x, 0.0f, 1.0f));
  }
  return set;
}

// 10 bits per axis of p in the box [lo, hi], interleaved (Morton order).
inline std::uint32_t morton30(glm::vec3 p, glm::vec3 lo, glm::vec3 hi) {
  const glm::vec3 q = glm::clamp((p - lo) / glm::max(hi - lo, glm::vec3(1e-6f)), 0.0f, 1.0f);
  const auto spread = [](std::uint32_t v) {
    v = (v * 0x00010001u) & 0xFF0000FFu;
    v = (v * 0x00000101u) & 0x0F00F00Fu;
    v = (v * 0x00000011u) & 0xC30C30C3u;
    v = (v * 0x00000005u) & 0x49249249u;
    return v;
  };
  const glm::uvec3 c = glm::uvec3(q * 1023.0f);
  return (spread(c.x) << 2) | (spread(c.y) << 1) | spread(c.z);
}

// The same segments reordered so that neighbours (one probe workgroup, one SIMD batch) share
// their target region, then their origin region: Morton order of the target, then of the origin,
// within the scene box. Measures what ray sorting would give shadow rays.
inline std::vector<gpu::BvhRay> sorted_by_target(std::vector<gpu::BvhRay> rays, glm::vec3 lo,
                                                 glm::vec3 hi) {
  std::vector<std::pair<std::uint64_t, std::size_t>> keys;
  keys.reserve(rays.size());
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const glm::vec3 o(rays[i].origin), t = o + glm::vec3(rays[i].direction);
    keys.push_back({(std::uint64_t{morton30(t, lo, hi)} << 30) | morton30(o, lo, hi), i});
  }
  std::sort(keys.begin(), keys.end());
  std::vector<gpu::BvhRay> out;
  out.reserve(rays.size());
  for (const auto& k : keys) out.push_back(rays[k.second]);
  return out;
}

}  // namespace lantern::lighting::test
