// Visibility benchmark (not a test): on a level (default night_market) at 320x180 and 640x360,
// Mrays/s of primary rays (one per pixel from the level camera) and of shadow-ray sets from the
// primary hits for each GPU variant -- compute BVH with texel-buffer fetches ("texel", the
// default), with storage-buffer fetches ("storage"), ray query ("rayquery") -- and the same
// traversal on one CPU thread, interleaved run by run, medians of --runs runs; plus CPU BVH build
// ms (all BLASes, the per-frame TLAS rebuild) and lavapipe BLAS/TLAS build ms (GPU timestamps).
// The anchor: Intel Embree 3 on the same rays (tests/visibility/embree_anchor.h; flat and
// two-level, single rays, --threads host threads), each project path's throughput as a ratio of
// Embree flat, and Embree's hit/miss agreement with the CPU traversal. "host": the renderer's host
// visibility backend (lighting/visibility/host_visibility.h: its own Embree scenes, streams of
// 256 rays through rtcOccluded1M) on the shadow-ray sets, and on the primary set its G-buffer
// trace (HostVisibility::trace_primary: the camera rays made from the frame constants,
// rtcIntersect1M), with its agreement (hit/miss, and the same triangle); on the "bsdf" set
// (closest hits from the primary hits, like restir.initial's BSDF candidates) its closest-hit
// trace (HostVisibility::trace_closest).
// "texel" and "cpu" trace the renderer's layout (lighting/bvh/scene_bvh.h: the fixed instances
// merged into one world-space tree, movers instanced); "texel two-level" and "cpu two-level" the
// same scene with every instance under the TLAS (the layout before the merge).
// "ris-160 sorted": the ris-160 rays reordered by target then origin (what ray sorting gives);
// "ris-160 by work": ordered by each ray's node count (an oracle: how much SIMD divergence costs).
// Shadow sets: "probe" (a light from the power alias table, every pick traced: the GPU test's
// rays), "baseline" and "ris-8"/"ris-160" (made like integrators.baseline and restir.initial's
// pick, tests/visibility/shading_ray_sets.h), each with its occluded fraction and work per ray
// (nodes entered, instances entered, triangle tests: tests/visibility/traversal_counter.h).
// Usage: visibility_bench [--level NAME] [--runs N] [--sizes 320x180,640x360] [--threads N]
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include "engine/level/level_loader.h"
#include "lighting/scene/frame_constants.h"
#include "lighting/scene/scene_data.h"
#include "lighting/visibility/ray_query_scene.h"
#include "tests/visibility/shading_ray_sets.h"
#include "tests/visibility/traversal_counter.h"
#include "tests/visibility/visibility_harness.h"
#include "lighting/visibility/host_visibility.h"
#include "tests/visibility/embree_anchor.h"

namespace lantern::lighting {
namespace {

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

std::string anchor_name(const test::EmbreeAnchor& anchor) {
  return std::string(test::embree_layout_name(anchor.layout()));
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
  unsigned threads = 2;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> sizes = {{320, 180}, {640, 360}};
  for (int i = 1; i + 1 < argc; i += 2) {
    if (std::strcmp(argv[i], "--level") == 0) level_name = argv[i + 1];
    if (std::strcmp(argv[i], "--runs") == 0) runs = std::max(1, std::atoi(argv[i + 1]));
    if (std::strcmp(argv[i], "--threads") == 0)
      threads = static_cast<unsigned>(std::max(1, std::atoi(argv[i + 1])));
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
  const std::vector<BvhInstanceDesc> descs = bvh_instance_descs(level);
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
  // The two-level layout: the same instances, none declared fixed.
  SceneBvh two_level_bvh;
  std::vector<BvhInstanceDesc> instanced = descs;
  for (BvhInstanceDesc& d : instanced) d.fixed = false;
  const double two_level_ms = wall_ms([&] {
    for (const Mesh& mesh : level.meshes)
      two_level_bvh.add_mesh(MeshBvh(mesh.positions, mesh.indices));
    two_level_bvh.set_instances(instanced);
  });
  VisibilityScene two_level_scene(device, two_level_bvh, VisibilityBackend::Bvh);
  fmt::print(
      "renderer BVH: {} of {} instances merged ({} world-space triangles); two-level BVH (every "
      "instance under the TLAS): build {:.1f} ms\n",
      data.bvh.merged_instance_count(), data.bvh.instance_count(), data.bvh.merged_triangle_count(),
      two_level_ms);
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

  std::vector<std::unique_ptr<test::EmbreeAnchor>> anchors;
  for (const test::EmbreeLayout layout : {test::EmbreeLayout::Flat, test::EmbreeLayout::TwoLevel})
    anchors.push_back(std::make_unique<test::EmbreeAnchor>(level, layout, threads));
  fmt::print("embree {} ({} threads): build flat {:.1f} ms, two-level {:.1f} ms\n",
             anchors[0]->version(), threads, anchors[0]->build_ms(), anchors[1]->build_ms());
  // The renderer's host backend (shadow rays only): its own scenes, streams of 256 rays.
  const HostVisibility host(device, data.bvh, bvh_instance_descs(level));
  fmt::print("host backend ({}, {} threads): {} of {} instances merged, built in {:.1f} ms\n",
             host.version(), host.threads(), host.merged_instances(), data.bvh.instance_count(),
             host.build_ms());

  std::vector<std::string> variants = {"texel", "storage"};
  if (rq_scene) variants.push_back("rayquery");
  std::map<std::string, std::unique_ptr<test::Probe>> probes;
  for (const std::string& v : variants)
    probes[v] = std::make_unique<test::Probe>(device, shaders, v == "texel" ? "" : v);

  struct RaySet {
    std::string name;
    std::uint32_t mode;
    std::vector<gpu::BvhRay> rays;
    std::string note;
  };
  for (const auto& [w, h] : sizes) {
    const std::vector<gpu::BvhRay> primary = test::camera_rays(level.camera, w, h);
    const gpu::FrameConstants primary_constants =
        make_frame_constants(level.camera, w, h, 0, 1, {});
    std::vector<RaySet> sets;
    sets.push_back({"primary", 0, primary, ""});
    sets.push_back({"bsdf", 0, test::bsdf_rays(level, data, primary, 77),
                    "closest hits from the primary hits, cosine about the normal (restir.initial's "
                    "BSDF candidates)"});
    sets.push_back(
        {"probe", 1,
         test::shadow_rays(data.bvh, primary, data.lights, data.scene_radius(), {}, 1234), ""});
    for (const std::uint32_t m : {0u, 8u, 160u}) {
      test::ShadingRaySet s = test::shading_shadow_rays(level, data, primary, m, 4321 + m);
      sets.push_back({m == 0 ? "baseline" : fmt::format("ris-{}", m), 1, std::move(s.rays),
                      fmt::format("{} of {} picks light nothing (no ray)", s.zero_contribution,
                                  s.surface_points)});
    }
    sets.push_back({"ris-160 sorted", 1,
                    test::sorted_by_target(sets.back().rays, data.bounds_min, data.bounds_max),
                    "the ris-160 rays in Morton order of target, then origin"});
    {
      // Diagnostic, not realizable: the ris-160 rays ordered by the nodes the renderer's traversal
      // visits for each, so SIMD neighbours do the same amount of work (no divergence left).
      const std::vector<gpu::BvhRay>& rays = sets[sets.size() - 2].rays;
      std::vector<std::pair<std::uint64_t, std::size_t>> work;
      for (std::size_t i = 0; i < rays.size(); ++i) {
        test::TraversalCounts one;
        (void)test::count_traversal(data.bvh, rays[i], 1, one);
        work.push_back({one.tlas_nodes + one.blas_nodes, i});
      }
      std::sort(work.begin(), work.end());
      std::vector<gpu::BvhRay> by_work;
      for (const auto& [nodes, i] : work) by_work.push_back(rays[i]);
      sets.push_back({"ris-160 by work", 1, std::move(by_work),
                      "the ris-160 rays ordered by their renderer-layout node count (oracle)"});
    }

    // Timings, interleaved: run -1 warms up (JIT at first dispatch).
    std::map<std::string, std::map<std::string, std::vector<double>>> ms;  // set -> path -> runs
    for (int r = -1; r < runs; ++r) {
      for (const RaySet& set : sets) {
        for (const std::string& v : variants) {
          const VisibilityScene& scene = v == "rayquery" ? *rq_scene : bvh_scene;
          double t = 0.0;
          probes[v]->run(scene, set.rays, set.mode, &t);
          if (r >= 0) ms[set.name][v].push_back(t);
        }
        double two_level_t = 0.0;
        probes["texel"]->run(two_level_scene, set.rays, set.mode, &two_level_t);
        if (r >= 0) ms[set.name]["texel two-level"].push_back(two_level_t);
        for (const auto& anchor : anchors) {
          double t = 0.0;
          (void)anchor->run(set.rays, set.mode, &t);
          if (r >= 0) ms[set.name][fmt::format("embree {}", anchor_name(*anchor))].push_back(t);
        }
        if (set.mode == 1) {
          std::vector<gpu::HostShadowRay> records = test::host_records(set.rays);
          const double t = wall_ms([&] { host.trace(records); });
          if (r >= 0) ms[set.name]["host"].push_back(t);
        } else if (set.name != "primary") {
          // restir.initial's closest hits: the records as its "closestemit" variant writes them.
          std::vector<gpu::HostClosestRay> records = test::host_closest_records(set.rays);
          const double t = wall_ms([&] { host.trace_closest(records); });
          if (r >= 0) ms[set.name]["host"].push_back(t);
        } else {
          // The host G-buffer's trace: the same pixels' camera rays, made from the frame constants.
          std::vector<glm::uvec2> hits(set.rays.size());
          const double t = wall_ms([&] { host.trace_primary(primary_constants, w, h, hits); });
          if (r >= 0) ms[set.name]["host"].push_back(t);
        }
      }
    }
    fmt::print("{}x{} (medians of {} interleaved runs; cpu: 1 thread, one run)\n", w, h, runs);
    for (const RaySet& set : sets) {
      std::vector<glm::uvec4> cpu;
      const double cpu_ms = wall_ms([&] { cpu = test::cpu_probe(data.bvh, set.rays, set.mode); });
      ms[set.name]["cpu"].push_back(cpu_ms);
      std::vector<glm::uvec4> cpu_two_level;
      ms[set.name]["cpu two-level"].push_back(
          wall_ms([&] { cpu_two_level = test::cpu_probe(two_level_bvh, set.rays, set.mode); }));
      const test::TraversalCounts two_level_counts =
          test::count_traversal(two_level_bvh, set.rays, set.mode);
      // Work per ray over the set, and apart for rays that hit / are blocked and those that miss /
      // get through.
      test::TraversalCounts counts, hit_counts, miss_counts;
      for (const gpu::BvhRay& ray : set.rays) {
        test::TraversalCounts one;
        const bool hit = test::count_traversal(data.bvh, ray, set.mode, one);
        for (test::TraversalCounts* c : {&counts, hit ? &hit_counts : &miss_counts}) {
          c->rays += one.rays, c->tlas_nodes += one.tlas_nodes, c->blas_nodes += one.blas_nodes;
          c->instances += one.instances, c->triangles += one.triangles, c->hits += one.hits;
        }
      }
      std::size_t cpu_hits = 0;
      for (const glm::uvec4& a : cpu) cpu_hits += set.mode == 0 ? a.x != ~0u : a.w == 0u;
      fmt::print(
          "  {:8s} {:7d} rays, {:5.1f}% {} | per ray: {:5.1f} TLAS + {:6.1f} BLAS nodes, "
          "{:5.1f} instances, {:6.1f} triangle tests{}{}\n",
          set.name, set.rays.size(),
          100.0 * static_cast<double>(cpu_hits) / std::max<std::size_t>(set.rays.size(), 1),
          set.mode == 0 ? "hit" : "occluded", counts.per_ray(counts.tlas_nodes),
          counts.per_ray(counts.blas_nodes), counts.per_ray(counts.instances),
          counts.per_ray(counts.triangles),
          counts.hits == cpu_hits ? "" : " (COUNTER DISAGREES WITH THE CPU TRAVERSAL)",
          set.note.empty() ? "" : "; " + set.note);
      const auto nodes = [](const test::TraversalCounts& c) {
        return c.per_ray(c.tlas_nodes + c.blas_nodes);
      };
      const char* hit_name = set.mode == 0 ? "hit" : "blocked";
      const char* miss_name = set.mode == 0 ? "missed" : "clear";
      fmt::print(
          "  {:8s} {} rays {:.1f} nodes, {:.1f} instances; {} rays {:.1f} nodes, {:.1f} "
          "instances\n",
          "", hit_name, nodes(hit_counts), hit_counts.per_ray(hit_counts.instances), miss_name,
          nodes(miss_counts), miss_counts.per_ray(miss_counts.instances));
      std::size_t two_level_same = 0;
      for (std::size_t i = 0; i < cpu.size(); ++i)
        two_level_same += set.mode == 0 ? (cpu[i].x == ~0u) == (cpu_two_level[i].x == ~0u)
                                        : cpu[i].w == cpu_two_level[i].w;
      fmt::print(
          "  {:8s} two-level layout: {:.1f} nodes, {:.1f} triangle tests per ray; agrees with the "
          "renderer layout's CPU traversal on {:.4f}%\n",
          "", nodes(two_level_counts), two_level_counts.per_ray(two_level_counts.triangles),
          100.0 * static_cast<double>(two_level_same) / std::max<std::size_t>(cpu.size(), 1));
      const double n = static_cast<double>(set.rays.size());
      std::string line = fmt::format("  {:8s} Mrays/s:", "");
      for (const auto& [path, runs_ms] : ms[set.name])
        line += fmt::format(" {} {:.2f} |", path, n / median(runs_ms) / 1e3);
      fmt::print("{}\n", line.substr(0, line.size() - 2));
      const double flat = median(ms[set.name]["embree flat"]);
      std::string ratios = fmt::format("  {:8s} vs embree flat:", "");
      for (const std::string& path :
           {std::string("texel"), std::string("texel two-level"), std::string("rayquery"),
            std::string("cpu"), std::string("cpu two-level"), std::string("embree two-level"),
            std::string("host")})
        if (ms[set.name].count(path))
          ratios += fmt::format(" {} {:.3f}x |", path, flat / median(ms[set.name][path]));
      std::string agree = " agreement with cpu:";
      for (const auto& anchor : anchors)
        agree += fmt::format(
            " {} {:.4f}%", anchor_name(*anchor),
            100.0 * test::probe_agreement(anchor->run(set.rays, set.mode), cpu, set.mode));
      if (set.mode == 1) {
        std::vector<gpu::HostShadowRay> records = test::host_records(set.rays);
        host.trace(records);
        std::size_t same = 0;
        for (std::size_t i = 0; i < cpu.size(); ++i)
          same += (cpu[i].w != 0u) == gpu::host_ray_visible(records[i]) ? 1u : 0u;
        agree += fmt::format(" host {:.4f}%", 100.0 * static_cast<double>(same) /
                                                  std::max<std::size_t>(cpu.size(), 1));
      } else {
        // The host names the triangle: the same hit or miss, and the same (instance, triangle)
        // where both hit. Primary rays through the host G-buffer's trace, the others as
        // restir.initial's closest-hit records.
        std::vector<glm::uvec2> hits(set.rays.size());
        if (set.name == "primary") {
          host.trace_primary(primary_constants, w, h, hits);
        } else {
          std::vector<gpu::HostClosestRay> records = test::host_closest_records(set.rays);
          host.trace_closest(records);
          for (std::size_t i = 0; i < records.size(); ++i)
            hits[i] = glm::uvec2(records[i].instance, records[i].primitive);
        }
        std::size_t same = 0, same_triangle = 0;
        for (std::size_t i = 0; i < cpu.size(); ++i) {
          const bool cpu_hit = cpu[i].x != ~0u, host_hit = hits[i].x != gpu::kNoInstance;
          same += cpu_hit == host_hit ? 1u : 0u;
          same_triangle += !cpu_hit || (host_hit && hits[i] == glm::uvec2(cpu[i])) ? 1u : 0u;
        }
        const double n_rays = static_cast<double>(std::max<std::size_t>(cpu.size(), 1));
        agree += fmt::format(" host {:.4f}% (same triangle {:.4f}%)",
                             100.0 * static_cast<double>(same) / n_rays,
                             100.0 * static_cast<double>(same_triangle) / n_rays);
      }
      fmt::print("{}{}\n", ratios.substr(0, ratios.size() - 2), agree);
    }
    fmt::print("  texel vs storage speed-up: primary {:.2f}x, probe shadow {:.2f}x\n",
               median(ms["primary"]["storage"]) / median(ms["primary"]["texel"]),
               median(ms["probe"]["storage"]) / median(ms["probe"]["texel"]));
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
