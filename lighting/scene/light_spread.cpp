#include "lighting/scene/light_spread.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "lighting/scene/scene_data.h"
#include "shared/color.h"
#include "shared/light_eval.h"
#include "shared/sampling.h"

namespace lantern::lighting {
namespace {

struct WorldTriangle {
  glm::vec3 p0, e1, e2;
};

// build_scene_data names each emitting instance's first triangle light (kInvalidLight: none).
bool emits(const gpu::GpuInstance& instance) { return instance.bvh.y != gpu::kInvalidLight; }

// The world-space triangles of the instances that do not emit (of every instance when all do),
// with the running sum of their areas.
std::vector<WorldTriangle> surface_triangles(const SceneData& scene, std::vector<double>& cdf) {
  bool any_dark = false;
  for (const gpu::GpuInstance& instance : scene.instances) any_dark |= !emits(instance);
  std::vector<WorldTriangle> out;
  double total = 0.0;
  for (const gpu::GpuInstance& instance : scene.instances) {
    if (any_dark && emits(instance)) continue;
    const glm::mat4& m = instance.object_to_world;
    const std::uint64_t first = instance.geometry.y;
    const std::uint64_t end =
        std::min<std::uint64_t>(first + instance.geometry.z, scene.indices.size());
    for (std::uint64_t k = first; k + 3 <= end; k += 3) {
      const auto at = [&](std::uint64_t i) {
        const std::size_t v = std::size_t{instance.geometry.w} + scene.indices[i];
        return v < scene.vertices.size()
                   ? glm::vec3(m * glm::vec4(glm::vec3(scene.vertices[v].position_u), 1.0f))
                   : glm::vec3(0.0f);
      };
      const glm::vec3 p0 = at(k), p1 = at(k + 1), p2 = at(k + 2);
      const WorldTriangle t{p0, p1 - p0, p2 - p0};
      const double area = 0.5 * glm::length(glm::cross(t.e1, t.e2));
      if (!(area > 0.0) || !std::isfinite(area)) continue;
      total += area;
      out.push_back(t);
      cdf.push_back(total);
    }
  }
  return out;
}

}  // namespace

LightSpread measure_light_spread(const SceneData& scene, std::uint32_t points, std::uint32_t draws,
                                 std::uint32_t seed) {
  LightSpread result;
  const LightTable& table = scene.lights;
  if (!table.has_power() || points == 0 || draws == 0) return result;
  std::vector<double> cdf;
  const std::vector<WorldTriangle> triangles = surface_triangles(scene, cdf);
  if (triangles.empty()) return result;

  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  const float radius = scene.scene_radius();
  double sum = 0.0;
  for (std::uint32_t p = 0; p < points; ++p) {
    // A point on the surfaces, by area.
    const double pick = std::uniform_real_distribution<double>(0.0, cdf.back())(rng);
    const std::size_t t = std::min<std::size_t>(
        std::upper_bound(cdf.begin(), cdf.end(), pick) - cdf.begin(), triangles.size() - 1);
    const WorldTriangle& tri = triangles[t];
    const glm::vec3 x =
        gpu::triangle_point(tri.p0, tri.p0 + tri.e1, tri.p0 + tri.e2,
                            gpu::triangle_sample_barycentrics({uniform(rng), uniform(rng)}));
    const glm::vec3 n = glm::normalize(glm::cross(tri.e1, tri.e2));
    // Moments of w = c / p over power draws (the 1/pi of the white surface cancels in the ratio).
    double m1 = 0.0, m2 = 0.0;
    for (std::uint32_t d = 0; d < draws; ++d) {
      const float u0 = uniform(rng), u1 = uniform(rng);
      const std::uint32_t i = table.sample(u0, u1);
      const gpu::GpuLight& light = table.lights()[i];
      const glm::vec3 y = gpu::light_eval_position(light, {uniform(rng), uniform(rng)}, x, radius);
      glm::vec3 l;
      const float geometry = gpu::light_eval_geometry(light, y, x, l);
      const double pdf = double{table.selection_pdf(i)} * gpu::light_eval_point_pdf(light);
      const double c = double{gpu::luminance(gpu::light_eval_radiance(light, y))} * geometry *
                       std::abs(glm::dot(n, l));
      const double w = pdf > 0.0 && std::isfinite(c) ? c / pdf : 0.0;
      m1 += w;
      m2 += w * w;
    }
    if (!(m1 > 0.0) || !std::isfinite(m2)) continue;
    m1 /= draws;
    m2 /= draws;
    sum += std::max(m2 / (m1 * m1) - 1.0, 0.0);
    ++result.points;
  }
  if (result.points > 0) result.spread = static_cast<float>(sum / result.points);
  return result;
}

}  // namespace lantern::lighting
