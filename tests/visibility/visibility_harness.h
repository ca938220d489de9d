// Shared by the visibility GPU test and benchmark: camera rays, shadow rays towards light points,
// and the probe kernel (shaders/tests/visibility_probe.comp) run through a VisibilityScene in any
// backend variant, with its GPU time.
#pragma once

#include <algorithm>
#include <glm/glm.hpp>
#include <random>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "engine/scene/camera.h"
#include "lighting/bvh/scene_bvh.h"
#include "lighting/frame/tile_order.h"
#include "lighting/lights/light_table.h"
#include "lighting/scene/frame_constants.h"
#include "lighting/visibility/visibility_scene.h"
#include "runtime/core/device.h"
#include "runtime/gpu/bindings.h"
#include "runtime/gpu/buffer.h"
#include "runtime/gpu/compute_pipeline.h"
#include "runtime/gpu/gpu_timer.h"
#include "runtime/gpu/shader_library.h"
#include "runtime/gpu/transfer.h"
#include "shared/host_visibility.h"
#include "shared/lights.h"

namespace lantern::lighting::test {

// One primary ray per pixel centre (row-major from the top-left), unbounded.
inline std::vector<gpu::BvhRay> camera_rays(const Camera& camera, std::uint32_t width,
                                            std::uint32_t height) {
  const glm::mat4 inv = glm::inverse(camera_view_proj(camera, width, height));
  std::vector<gpu::BvhRay> rays;
  rays.reserve(std::size_t{width} * height);
  for (std::uint32_t y = 0; y < height; ++y)
    for (std::uint32_t x = 0; x < width; ++x) {
      const glm::vec2 ndc(
          2.0f * (static_cast<float>(x) + 0.5f) / static_cast<float>(width) - 1.0f,
          2.0f * (static_cast<float>(y) + 0.5f) / static_cast<float>(height) - 1.0f);
      glm::vec4 n = inv * glm::vec4(ndc, 0.0f, 1.0f);
      glm::vec4 f = inv * glm::vec4(ndc, 0.5f, 1.0f);
      const glm::vec3 origin = glm::vec3(n) / n.w;
      const glm::vec3 dir = glm::normalize(glm::vec3(f) / f.w - origin);
      rays.push_back(gpu::bvh_make_ray(camera.position, dir, 0.0f, gpu::kBvhMiss));
    }
  return rays;
}

// A point on light `index`: uniform on a triangle, the position of a point/spot light, or a point
// 2 * radius back along a directional light.
inline glm::vec3 light_point(const gpu::GpuLight& light, const glm::vec3& from, float radius,
                             std::mt19937& rng) {
  const std::uint32_t kind = glm::floatBitsToUint(light.p0.w);
  if (kind == gpu::kLightTriangle) {
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    float a = u(rng), b = u(rng);
    if (a + b > 1.0f) a = 1.0f - a, b = 1.0f - b;
    return glm::vec3(light.p0) + a * glm::vec3(light.p1) + b * glm::vec3(light.p2);
  }
  if (kind == gpu::kLightDirectional)
    return from - 2.0f * radius * glm::normalize(glm::vec3(light.p1));
  return glm::vec3(light.p0);
}

// Shadow rays (origin, target - origin) from every CPU primary hit to a light drawn from the
// power alias table (or, with a fixed light list, to lights[k % size] for the k-th hit).
inline std::vector<gpu::BvhRay> shadow_rays(const SceneBvh& bvh,
                                            std::span<const gpu::BvhRay> primary,
                                            const LightTable& lights, float radius,
                                            std::span<const std::uint32_t> fixed_lights,
                                            std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<gpu::BvhRay> rays;
  for (const gpu::BvhRay& ray : primary) {
    gpu::BvhHit hit;
    if (!bvh.trace_closest(ray, hit)) continue;
    const glm::vec3 p = glm::vec3(ray.origin) + hit.t * glm::vec3(ray.direction);
    std::uint32_t index = 0;
    if (!fixed_lights.empty()) {
      index = fixed_lights[rays.size() % fixed_lights.size()];
    } else {
      const float u0 = u(rng), u1 = u(rng);
      index = lights.sample(u0, u1);
    }
    const glm::vec3 target = light_point(lights.lights()[index], p, radius, rng);
    rays.push_back(gpu::bvh_make_ray(p, target - p, 0.0f, 1.0f));
  }
  return rays;
}

// The host backend's records of probe-format shadow rays (segment origin -> origin + direction),
// as the emit variant writes them, slot = ray index.
inline std::vector<gpu::HostShadowRay> host_records(std::span<const gpu::BvhRay> rays) {
  std::vector<gpu::HostShadowRay> records;
  records.reserve(rays.size());
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const glm::vec3 origin(rays[i].origin);
    records.push_back(gpu::host_ray_segment(origin, origin + glm::vec3(rays[i].direction),
                                            static_cast<std::uint32_t>(i)));
  }
  return records;
}

// The host backend's closest-hit records of probe-format rays (origin, direction, tmax =
// direction.w), as restir.initial's "closestemit" variant writes them, slot = ray index.
inline std::vector<gpu::HostClosestRay> host_closest_records(std::span<const gpu::BvhRay> rays) {
  std::vector<gpu::HostClosestRay> records;
  records.reserve(rays.size());
  for (std::size_t i = 0; i < rays.size(); ++i) {
    records.push_back(gpu::host_closest_ray(glm::vec3(rays[i].origin),
                                            glm::vec3(rays[i].direction), rays[i].direction.w,
                                            static_cast<std::uint32_t>(i)));
  }
  return records;
}

// The CPU answers in the probe's format (x = instance or ~0u, w = visible for mode 1).
inline std::vector<glm::uvec4> cpu_probe(const SceneBvh& bvh, std::span<const gpu::BvhRay> rays,
                                         std::uint32_t mode) {
  std::vector<glm::uvec4> out;
  out.reserve(rays.size());
  for (const gpu::BvhRay& ray : rays) {
    glm::uvec4 r(~0u, 0u, 0u, 0u);
    if (mode == 0) {
      gpu::BvhHit hit;
      if (bvh.trace_closest(ray, hit))
        r = glm::uvec4(hit.instance, hit.primitive, glm::floatBitsToUint(hit.t), 0u);
    } else {
      const glm::vec3 o(ray.origin);
      r.w = bvh.visible(o, o + glm::vec3(ray.direction)) ? 1u : 0u;
    }
    out.push_back(r);
  }
  return out;
}

struct ProbePush {
  std::uint32_t ray_count;
  std::uint32_t mode;
  std::uint32_t group_count;
  std::uint32_t group_stride;
};

// The probe pipeline of one variant ("" = BVH storage buffers, "texel", "rayquery").
class Probe {
 public:
  Probe(runtime::Device& device, runtime::ShaderLibrary& shaders, std::string_view variant)
      : device_(device),
        pipeline_(device, shaders.load("tests/visibility_probe.comp", variant),
                  {.name = "visibility.probe"}),
        timer_(device, 4) {}

  // Traces `rays` (mode 0 closest, 1 shadow); returns the results and sets gpu_ms.
  std::vector<glm::uvec4> run(const VisibilityScene& scene, std::span<const gpu::BvhRay> rays,
                              std::uint32_t mode, double* gpu_ms = nullptr) {
    const std::size_t n = std::max<std::size_t>(rays.size(), 1);
    if (!rays_ || rays_.size() < n * sizeof(gpu::BvhRay)) {
      rays_ = runtime::Buffer(device_, {.size = n * sizeof(gpu::BvhRay),
                                        .usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                        .memory = runtime::MemoryUsage::DeviceLocal,
                                        .name = "probe.rays"});
      results_ = runtime::Buffer(device_, {.size = n * sizeof(glm::uvec4),
                                           .usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                           .memory = runtime::MemoryUsage::Readback,
                                           .name = "probe.results"});
    }
    if (!rays.empty()) runtime::upload_buffer(device_, rays_, rays);
    const auto count = static_cast<std::uint32_t>(rays.size());
    const std::uint32_t groups = std::max<std::uint32_t>((count + 63) / 64, 1);
    // Neighbouring workgroups land far apart, so both lavapipe threads get a mix of cheap and
    // expensive rays (the shuffled order the passes use).
    const std::uint32_t stride = lighting::tile_stride(groups);
    runtime::Bindings bindings(pipeline_);
    scene.bind(bindings);
    bindings.buffer("probe_rays", rays_).buffer("probe_results", results_);
    device_.submit_and_wait([&](VkCommandBuffer cmd) {
      timer_.reset(cmd);
      auto scope = timer_.scope(cmd, "visibility.probe");
      pipeline_.bind(cmd, bindings);
      pipeline_.push_constants(cmd, ProbePush{count, mode, groups, stride});
      pipeline_.dispatch(cmd, groups);
    });
    if (gpu_ms != nullptr) *gpu_ms = timer_.resolve()[0].ms;
    std::vector<glm::uvec4> all = runtime::read_buffer<glm::uvec4>(device_, results_);
    all.resize(rays.size());
    return all;
  }

 private:
  runtime::Device& device_;
  runtime::ComputePipeline pipeline_;
  runtime::GpuTimer timer_;
  runtime::Buffer rays_;
  runtime::Buffer results_;
};

}  // namespace lantern::lighting::test
