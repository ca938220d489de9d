// Visibility benchmark (not a test): on a level (default night_market) at 320x180 and 640x360,
// Mrays/s of primary rays (one per pixel from the level camera) and shadow rays (from each primary
// hit towards a light drawn from the power alias table) for each GPU variant -- compute BVH with
// texel-buffer fetches ("texel", the default), with storage-buffer fetches ("storage"), ray query
// ("rayquery") --
// interleaved run by run, medians of --runs runs; plus CPU BVH build ms (all BLASes, the per-frame
// TLAS rebuild) and lavapipe BLAS/TLAS build ms (GPU timestamps).
// Usage: visibility_bench [--level NAME] [--runs N] [--sizes 320x180,640x360]
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include "engine/level/level_loader.h"
#include "lighting/scene/scene_data.h"
#include "lighting/visibility/ray_query_scene.h"
#include "tests/visibility/visibility_harness.h"

namespace lantern::lighting {
namespace {

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

template <class F>
double wall_ms(F&& f) {
  const auto t0 = std::chrono::steady_clock::now();
  f();
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

int run(int argc, char** argv) {
  std::string level_name = "night_market";
  int runs = 5;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> sizes = {{320, 180}, {640, 360}};
  for (int i = 1; i + 1 < argc; i += 2) {
    if (std::strcmp(argv[i], "--level") == 0) level_name = argv[i + 1];
    if (std::strcmp(argv[i], "--runs") == 0) runs = std::max(1, std::atoi(argv[i + 1]));
    if (std::strcmp(argv[i], "--sizes") == 0) {
      sizes.clear();
      std::string s = argv[i + 1];
      for (std::size_t p = 0; p < s.size();) {
        std::size_t q = s.find(',', p);
        if (q == std::string::npos) q = s.size();
        unsigned w = 0, h = 0;
        if (std::sscanf(s.substr(p, q - p).c_str(), "%ux%u", &w, &h) == 2) sizes.push_back({w, h});
        p = q + 1;
      }
    }
  }

  const Level level = load_level_argument(level_name);
  SceneData data;
  const double scene_ms = wall_ms([&] { data = build_scene_data(level); });
  std::size_t triangles = 0;
  for (const Instance& inst : level.instances)
    triangles += level.meshes[inst.mesh].triangle_count();
  fmt::print(
      "level {}: {} meshes, {} instances, {} instanced triangles, {} lights; "
      "build_scene_data {:.1f} ms\n",
      level_name, level.meshes.size(), level.instances.size(), triangles,
      data.lights.lights().size(), scene_ms);

  // CPU BVH build times.
  std::vector<double> blas_ms, tlas_ms;
  std::vector<BvhInstanceDesc> descs;
  for (std::size_t i = 0; i < level.instances.size(); ++i)
    descs.push_back(
        {level.instances[i].mesh, level.instances[i].world, static_cast<std::uint32_t>(i)});
  for (int r = 0; r < 3; ++r) {
    SceneBvh bvh;
    blas_ms.push_back(wall_ms([&] {
      for (const Mesh& mesh : level.meshes) bvh.add_mesh(MeshBvh(mesh.positions, mesh.indices));
    }));
  }
  for (int r = 0; r < 10; ++r) tlas_ms.push_back(wall_ms([&] { data.bvh.set_instances(descs); }));
  fmt::print(
      "cpu bvh: BLAS all meshes {:.1f} ms, TLAS rebuild (set_instances) {:.2f} ms "
      "(medians of 3 / 10; multithreaded builder)\n",
      median(blas_ms), median(tlas_ms));

  runtime::Device device({.selector = "auto"});
  runtime::ShaderLibrary shaders;
  VisibilityScene bvh_scene(device, data.bvh, VisibilityBackend::Bvh);
  std::unique_ptr<VisibilityScene> rq_scene;
  if (device.caps().ray_query) {
    std::vector<double> rq_blas, rq_tlas, rq_tlas_write;
    const double create_ms = wall_ms([&] {
      rq_scene = std::make_unique<VisibilityScene>(device, data.bvh, VisibilityBackend::RayQuery);
    });
    RayQueryScene& rq = const_cast<RayQueryScene&>(*rq_scene->ray_query());
    runtime::GpuTimer timer(device, 4);
    for (int r = 0; r < 3; ++r) {
      device.submit_and_wait([&](VkCommandBuffer cmd) {
        timer.reset(cmd);
        auto s = timer.scope(cmd, "blas");
        rq.record_blas_builds(cmd);
        runtime::record_acceleration_structure_barrier(device, cmd);
      });
      rq_blas.push_back(timer.resolve()[0].ms);
    }
    for (int r = 0; r < 10; ++r) {
      rq_tlas_write.push_back(wall_ms([&] { rq.write_instances(data.bvh); }));
      device.submit_and_wait([&](VkCommandBuffer cmd) {
        timer.reset(cmd);
        auto s = timer.scope(cmd, "tlas");
        rq.record_tlas_build(cmd);
        runtime::record_acceleration_structure_barrier(device, cmd);
      });
      rq_tlas.push_back(timer.resolve()[0].ms);
    }
    fmt::print(
        "ray query ({} BLAS): BLAS all meshes {:.1f} ms GPU, TLAS {:.2f} ms GPU + {:.2f} ms "
        "instance records (CPU); whole setup incl. uploads {:.1f} ms wall\n",
        rq.blas_count(), median(rq_blas), median(rq_tlas), median(rq_tlas_write), create_ms);
  }

  std::vector<std::string> variants = {"texel", "storage"};
  if (rq_scene) variants.push_back("rayquery");
  std::map<std::string, std::unique_ptr<test::Probe>> probes;
  for (const std::string& v : variants)
    probes[v] = std::make_unique<test::Probe>(device, shaders, v == "texel" ? "" : v);

  for (const auto& [w, h] : sizes) {
    const std::vector<gpu::BvhRay> primary = test::camera_rays(level.camera, w, h);
    const std::vector<gpu::BvhRay> shadow =
        test::shadow_rays(data.bvh, primary, data.lights, data.scene_radius(), {}, 1234);
    std::map<std::string, std::vector<double>> primary_ms, shadow_ms;
    for (int r = -1; r < runs; ++r) {  // run -1 warms up (JIT at first dispatch)
      for (const std::string& v : variants) {
        const VisibilityScene& scene = v == "rayquery" ? *rq_scene : bvh_scene;
        double ms = 0.0;
        probes[v]->run(scene, primary, 0, &ms);
        if (r >= 0) primary_ms[v].push_back(ms);
        probes[v]->run(scene, shadow, 1, &ms);
        if (r >= 0) shadow_ms[v].push_back(ms);
      }
    }
    std::vector<double> cpu_ms;
    cpu_ms.push_back(wall_ms([&] { (void)test::cpu_probe(data.bvh, primary, 0); }));
    fmt::print("{}x{}: {} primary rays, {} shadow rays (medians of {} interleaved runs)\n", w, h,
               primary.size(), shadow.size(), runs);
    for (const std::string& v : variants) {
      const double p = median(primary_ms[v]), s = median(shadow_ms[v]);
      fmt::print("  {:9s} primary {:7.2f} ms {:6.2f} Mrays/s | shadow {:7.2f} ms {:6.2f} Mrays/s\n",
                 v, p, primary.size() / p / 1e3, s, shadow.size() / s / 1e3);
    }
    fmt::print("  texel vs storage speed-up: primary {:.2f}x, shadow {:.2f}x\n",
               median(primary_ms["storage"]) / median(primary_ms["texel"]),
               median(shadow_ms["storage"]) / median(shadow_ms["texel"]));
    fmt::print("  cpu (1 thread, same traversal) primary {:.2f} Mrays/s\n",
               primary.size() / median(cpu_ms) / 1e3);
  }
  return 0;
}

}  // namespace
}  // namespace lantern::lighting

int main(int argc, char** argv) {
  try {
    return lantern::lighting::run(argc, argv);
  } catch (const std::exception& e) {
    fmt::print(stderr, "visibility_bench: {}\n", e.what());
    return 1;
  }
}
