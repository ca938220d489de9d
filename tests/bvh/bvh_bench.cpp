// BVH benchmark (not a test): SAH build time with 1 and 2 threads, and CPU traversal throughput
// for coherent primary-like rays (640x360 pinhole camera, 8x8 tiles) and incoherent shadow rays
// (from the primary hits toward random points), on 100k and 1M triangle scenes.
// Usage: bvh_bench [--quick]   (--quick: 100k scenes only)
#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstring>
#include <ctime>
#include <random>
#include <thread>
#include <vector>

#include "lighting/bvh/scene_bvh.h"

namespace {

using lantern::lighting::BvhBuildOptions;
using lantern::lighting::BvhInstanceDesc;
using lantern::lighting::MeshBvh;
using lantern::lighting::SceneBvh;
namespace gpu = lantern::gpu;
using Clock = std::chrono::steady_clock;

struct Mesh {
  std::vector<glm::vec3> positions;
  std::vector<std::uint32_t> indices;
  glm::vec3 eye, look_at;
};

// Random triangles in [-1, 1]^3, edge length scaled so the soup is moderately dense.
Mesh random_soup(std::uint32_t count) {
  std::mt19937 rng(1);
  std::uniform_real_distribution<float> c(-1.0f, 1.0f);
  const float size = 2.0f / std::cbrt(static_cast<float>(count));
  std::uniform_real_distribution<float> o(-size, size);
  Mesh m;
  for (std::uint32_t t = 0; t < count; ++t) {
    const glm::vec3 centre(c(rng), c(rng), c(rng));
    for (int v = 0; v < 3; ++v) {
      m.indices.push_back(static_cast<std::uint32_t>(m.positions.size()));
      m.positions.push_back(centre + glm::vec3(o(rng), o(rng), o(rng)));
    }
  }
  m.eye = glm::vec3(0.3f, 0.4f, 3.0f);
  m.look_at = glm::vec3(0.0f);
  return m;
}

// A rolling terrain grid of about `count` triangles (shared vertices), seen from above at an angle.
Mesh terrain(std::uint32_t count) {
  const auto n = static_cast<std::uint32_t>(std::sqrt(static_cast<float>(count) / 2.0f));
  Mesh m;
  for (std::uint32_t z = 0; z <= n; ++z)
    for (std::uint32_t x = 0; x <= n; ++x) {
      const float fx = -1.0f + 2.0f * static_cast<float>(x) / static_cast<float>(n);
      const float fz = -1.0f + 2.0f * static_cast<float>(z) / static_cast<float>(n);
      const float h = 0.15f * std::sin(7.0f * fx) * std::cos(5.0f * fz) +
                      0.05f * std::sin(31.0f * fx + 17.0f * fz);
      m.positions.emplace_back(fx, h, fz);
    }
  for (std::uint32_t z = 0; z < n; ++z)
    for (std::uint32_t x = 0; x < n; ++x) {
      const std::uint32_t a = z * (n + 1) + x, b = a + 1, c = a + n + 1, d = c + 1;
      m.indices.insert(m.indices.end(), {a, c, b, b, c, d});
    }
  m.eye = glm::vec3(0.0f, 0.8f, 1.6f);
  m.look_at = glm::vec3(0.0f, 0.0f, -0.2f);
  return m;
}

double ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// Runs body(i) for i in [0, count) on `threads` threads, interleaving blocks of 64 (8x8 tiles).
template <typename F>
double run_parallel_ms(std::uint32_t count, std::uint32_t threads, F&& body) {
  std::atomic<std::uint32_t> next{0};
  const auto start = Clock::now();
  std::vector<std::thread> pool;
  for (std::uint32_t t = 0; t < threads; ++t)
    pool.emplace_back([&] {
      for (std::uint32_t block; (block = next.fetch_add(64)) < count;)
        for (std::uint32_t i = block; i < std::min(block + 64, count); ++i) body(i);
    });
  for (std::thread& th : pool) th.join();
  return ms_since(start);
}

void bench_scene(const char* name, const Mesh& mesh) {
  const std::uint32_t triangles = static_cast<std::uint32_t>(mesh.indices.size() / 3);
  double build_ms[2] = {0.0, 0.0};
  double build_cpu_ratio = 0.0;  // process CPU time / wall time of the 2-thread build
  MeshBvh blas;
  for (std::uint32_t threads : {1u, 2u}) {
    BvhBuildOptions options;
    options.thread_count = threads;
    double best = 1e30;
    for (int rep = 0; rep < 2; ++rep) {
      const auto start = Clock::now();
      const std::clock_t cpu_start = std::clock();
      blas = MeshBvh(mesh.positions, mesh.indices, options);
      const double wall = ms_since(start);
      if (wall < best)
        build_cpu_ratio =
            1e3 * static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC / wall;
      best = std::min(best, wall);
    }
    build_ms[threads - 1] = best;
  }
  const auto refit_start = Clock::now();
  blas.refit(mesh.positions);
  const double refit_ms = ms_since(refit_start);
  const std::size_t node_count = blas.nodes().size();

  SceneBvh scene;
  BvhInstanceDesc instance;
  instance.mesh = scene.add_mesh(std::move(blas));
  scene.set_instances({&instance, 1});

  // Primary rays in 8x8 tiles (ray index -> tile-major pixel order).
  const std::uint32_t width = 640, height = 360, pixels = width * height;
  const glm::vec3 forward = glm::normalize(mesh.look_at - mesh.eye);
  const glm::vec3 right = glm::normalize(glm::cross(forward, glm::vec3(0.0f, 1.0f, 0.0f)));
  const glm::vec3 up = glm::cross(right, forward);
  const float tan_half = std::tan(0.5f * 0.9f);
  const float aspect = static_cast<float>(width) / static_cast<float>(height);
  auto primary_ray = [&](std::uint32_t i) {
    const std::uint32_t tile = i / 64, in_tile = i % 64, tiles_x = width / 8;
    const std::uint32_t px = (tile % tiles_x) * 8 + in_tile % 8,
                        py = (tile / tiles_x) * 8 + in_tile / 8;
    const float sx = (2.0f * (static_cast<float>(px) + 0.5f) / static_cast<float>(width) - 1.0f) *
                     tan_half * aspect;
    const float sy =
        (1.0f - 2.0f * (static_cast<float>(py) + 0.5f) / static_cast<float>(height)) * tan_half;
    return gpu::bvh_make_ray(mesh.eye, glm::normalize(forward + sx * right + sy * up), 0.0f,
                             gpu::kBvhMiss);
  };
  std::vector<glm::vec3> hit_points(pixels);
  std::vector<std::uint8_t> hit_any(pixels, 0);
  std::vector<glm::vec3> lights(64);
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> u(-1.2f, 1.2f);
  for (glm::vec3& l : lights) l = glm::vec3(u(rng), 0.6f + 0.4f * u(rng), u(rng));

  double primary_ms[2], shadow_ms[2];
  std::uint32_t hits = 0, occluded = 0;
  for (std::uint32_t threads : {1u, 2u}) {
    primary_ms[threads - 1] = run_parallel_ms(pixels, threads, [&](std::uint32_t i) {
      gpu::BvhRay ray = primary_ray(i);
      gpu::BvhHit hit;
      hit_any[i] = scene.trace_closest(ray, hit) ? 1 : 0;
      hit_points[i] = glm::vec3(ray.origin) + hit.t * glm::vec3(ray.direction);
    });
    // Shadow rays: each pixel toward a light chosen by a hash (incoherent across neighbours).
    std::atomic<std::uint32_t> blocked{0};
    shadow_ms[threads - 1] = run_parallel_ms(pixels, threads, [&](std::uint32_t i) {
      const glm::vec3 origin = hit_any[i] ? hit_points[i] : mesh.eye;
      const glm::vec3 target = lights[(i * 2654435761u >> 7) % lights.size()];
      if (!scene.visible(origin, target)) blocked.fetch_add(1, std::memory_order_relaxed);
    });
    occluded = blocked.load();
  }
  for (std::uint8_t h : hit_any) hits += h;
  const double mrays = static_cast<double>(pixels) * 1e-3;  // rays / ms -> Mrays/s factor
  fmt::print(
      "{:<8} {:>8} tris {:>8} nodes | build 1T {:7.1f} ms  2T {:7.1f} ms (cpu/wall {:.2f})  refit "
      "{:6.1f} ms | "
      "primary 1T {:5.2f} 2T {:5.2f} Mrays/s ({:.0f}% hit) | shadow 1T {:5.2f} 2T {:5.2f} Mrays/s "
      "({:.0f}% blocked)\n",
      name, triangles, node_count, build_ms[0], build_ms[1], build_cpu_ratio, refit_ms,
      mrays / primary_ms[0], mrays / primary_ms[1], 100.0 * hits / pixels, mrays / shadow_ms[0],
      mrays / shadow_ms[1], 100.0 * occluded / pixels);
}

}  // namespace

int main(int argc, char** argv) {
  const bool quick = argc > 1 && std::strcmp(argv[1], "--quick") == 0;
  fmt::print("bvh_bench: binned SAH (16 bins, leaves <= 4), 640x360 rays, {} hardware threads\n",
             std::thread::hardware_concurrency());
  bench_scene("soup", random_soup(100000));
  bench_scene("terrain", terrain(100000));
  if (!quick) {
    bench_scene("soup", random_soup(1000000));
    bench_scene("terrain", terrain(1000000));
  }
  return 0;
}
