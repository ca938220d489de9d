// The host visibility backend's Embree scene answers shadow rays like the project's CPU traversal
// (SceneBvh::visible): on night_market's power-sampled and ReSTIR-like (RIS over 8 candidates)
// shadow rays at 160x90 on >= 99.9% of rays (the bar for every visibility path), and on
// cornell_lights after instances moved (an instanced mover and a fixed instance that leaves the
// merged geometry). Closest hits (restir.initial's BSDF candidates) name the CPU traversal's
// triangle on camera rays and BSDF-like rays from their hits on >= 99.9% of rays, before and
// after instances moved. Records without a ray stay visible (shadow) or miss (closest); a level
// with alpha-tested materials is refused by name.
#include "lighting/visibility/host_visibility.h"

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>
#include <cmath>
#include <limits>
#include <vector>

#include "engine/level/level_loader.h"
#include "lighting/scene/scene_data.h"
#include "tests/runtime/gpu_test_support.h"
#include "tests/visibility/shading_ray_sets.h"
#include "tests/visibility/visibility_harness.h"

namespace lantern::lighting::test {
namespace {

struct Answers {
  double agreement = 0.0;
  std::size_t blocked = 0;
  std::size_t visible = 0;
};

Answers compare_with_cpu(const HostVisibility& host, const SceneBvh& bvh,
                         std::span<const gpu::BvhRay> rays) {
  std::vector<gpu::HostShadowRay> records = host_records(rays);
  host.trace(records);
  Answers a;
  std::size_t same = 0;
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const glm::vec3 origin(rays[i].origin);
    const bool cpu = bvh.visible(origin, origin + glm::vec3(rays[i].direction));
    const bool embree = gpu::host_ray_visible(records[i]);
    same += cpu == embree ? 1 : 0;
    (embree ? a.visible : a.blocked) += 1;
  }
  a.agreement = static_cast<double>(same) / static_cast<double>(rays.size());
  return a;
}

// The host's closest hits against the CPU traversal's: the same miss, or the same instance and
// triangle with barycentrics within 1e-3 and distances within 1e-3 relative.
struct ClosestAnswers {
  double agreement = 0.0;
  std::size_t hits = 0;
  std::size_t misses = 0;
  std::size_t traced = 0;  // what trace_closest reported
};

ClosestAnswers compare_closest_with_cpu(const HostVisibility& host, const SceneBvh& bvh,
                                        std::span<const gpu::BvhRay> rays) {
  std::vector<gpu::HostClosestRay> records = host_closest_records(rays);
  ClosestAnswers a;
  a.traced = host.trace_closest(records);
  std::size_t same = 0;
  for (std::size_t i = 0; i < rays.size(); ++i) {
    gpu::BvhHit cpu;
    const bool cpu_found = bvh.trace_closest(rays[i], cpu);
    const gpu::HostClosestRay& r = records[i];
    const bool found = gpu::host_closest_found(r);
    bool agrees = found == cpu_found;
    if (agrees && found) {
      agrees = r.instance == cpu.instance && r.primitive == cpu.primitive &&
               std::abs(r.u - cpu.u) <= 1e-3f && std::abs(r.v - cpu.v) <= 1e-3f &&
               std::abs(r.ray.tfar - cpu.t) <= 1e-3f * cpu.t;
    }
    same += agrees ? 1u : 0u;
    (found ? a.hits : a.misses) += 1;
  }
  a.agreement = static_cast<double>(same) / static_cast<double>(rays.size());
  return a;
}

class HostVisibilityTest : public runtime::test::GpuTest {};

TEST_F(HostVisibilityTest, ShadowRaysAgreeWithTheCpuTraversalOnNightMarket) {
  const Level level = load_level_argument("night_market");
  const SceneData data = build_scene_data(level);
  const std::vector<BvhInstanceDesc> descs = bvh_instance_descs(level);
  const HostVisibility host(device, data.bvh, descs);
  EXPECT_GT(host.merged_instances(), descs.size() / 2) << "night_market's fixed instances";
  const std::vector<gpu::BvhRay> primary = camera_rays(level.camera, 160, 90);
  const std::vector<gpu::BvhRay> probe =
      shadow_rays(data.bvh, primary, data.lights, data.scene_radius(), {}, 7);
  const ShadingRaySet ris = shading_shadow_rays(level, data, primary, 8, 9);
  for (const auto* rays : {&probe, &ris.rays}) {
    ASSERT_GT(rays->size(), 1000u);
    const Answers a = compare_with_cpu(host, data.bvh, *rays);
    EXPECT_GE(a.agreement, 0.999);
    EXPECT_GT(a.blocked, rays->size() / 20) << "some rays must be blocked";
    EXPECT_GT(a.visible, rays->size() / 100) << "some rays must get through";
  }
}

TEST_F(HostVisibilityTest, ClosestHitsAgreeWithTheCpuTraversalOnNightMarket) {
  const Level level = load_level_argument("night_market");
  const SceneData data = build_scene_data(level);
  const HostVisibility host(device, data.bvh, bvh_instance_descs(level));
  // Camera rays, and rays like restir.initial's BSDF candidates from their hits (the sky above
  // the market: some miss).
  const std::vector<gpu::BvhRay> primary = camera_rays(level.camera, 160, 90);
  const std::vector<gpu::BvhRay> bsdf = bsdf_rays(level, data, primary, 11);
  for (const auto* rays : {&primary, &bsdf}) {
    ASSERT_GT(rays->size(), 1000u);
    const ClosestAnswers a = compare_closest_with_cpu(host, data.bvh, *rays);
    EXPECT_EQ(a.traced, rays->size()) << "every record held a ray";
    EXPECT_GE(a.agreement, 0.999);
    EXPECT_GT(a.hits, rays->size() / 10) << "some rays must hit";
    EXPECT_GT(a.misses, rays->size() / 100) << "some rays must escape";
  }
}

TEST_F(HostVisibilityTest, FollowsMovedInstances) {
  const Level level = load_level_argument("cornell_lights");
  SceneData data = build_scene_data(level);
  std::vector<BvhInstanceDesc> descs = bvh_instance_descs(level);
  HostVisibility host(device, data.bvh, descs);
  const std::size_t merged = host.merged_instances();
  ASSERT_GT(merged, 0u);
  const std::vector<gpu::BvhRay> primary = camera_rays(level.camera, 96, 54);
  const std::vector<gpu::BvhRay> rays =
      shadow_rays(data.bvh, primary, data.lights, data.scene_radius(), {}, 3);
  // Every instance moves: the fixed ones leave the merged geometry, the others are re-placed.
  for (int step = 1; step <= 2; ++step) {
    for (BvhInstanceDesc& d : descs) {
      d.object_to_world =
          glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.07f, 0.03f)) * d.object_to_world;
    }
    data.bvh.set_instances(descs);
    host.update(descs);
    const Answers a = compare_with_cpu(host, data.bvh, rays);
    EXPECT_GE(a.agreement, 0.999) << "step " << step;
    EXPECT_GT(a.blocked, 0u);
    EXPECT_GT(a.visible, 0u);
    // Closest hits name the moved instances (merged and instanced alike) as the BVH does.
    const ClosestAnswers c = compare_closest_with_cpu(host, data.bvh, primary);
    EXPECT_GE(c.agreement, 0.999) << "step " << step;
    EXPECT_GT(c.hits, 0u);
  }
  EXPECT_EQ(host.merged_instances(), 0u) << "moved fixed instances leave the merged geometry";
}

TEST_F(HostVisibilityTest, RecordsWithoutARayStayVisible) {
  const Level level = load_level_argument("cornell_lights");
  const SceneData data = build_scene_data(level);
  const HostVisibility host(device, data.bvh, bvh_instance_descs(level));
  // Slots the pass asked nothing of, points closer than two epsilons, and non-finite segments
  // (the emit variant writes no ray for them) read as visible, as the other backends answer.
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  const glm::vec3 p(0.1f, 0.2f, 0.3f);
  std::vector<gpu::HostShadowRay> records(300, gpu::host_ray_none());
  records.push_back(gpu::host_ray_segment(p, p + glm::vec3(1e-7f), 1));
  records.push_back(gpu::host_ray_segment(glm::vec3(nan), p, 2));
  records.push_back(gpu::host_ray_segment(p, glm::vec3(inf, 0.0f, 0.0f), 3));
  records.push_back(gpu::host_ray_segment(p, glm::vec3(3e19f, 0.0f, 0.0f), 4));
  // The degenerate segments keep their slot (the resolve pass stores their verdict) but are
  // inactive for Embree (tnear > tfar).
  for (std::size_t i = 300; i < records.size(); ++i) {
    EXPECT_TRUE(gpu::host_ray_traced(records[i])) << "record " << i << " lost its slot";
    EXPECT_FALSE(gpu::host_ray_active(records[i])) << "record " << i << " holds an active ray";
  }
  EXPECT_FALSE(gpu::host_ray_traced(records.front()));
  host.trace(records);
  for (const gpu::HostShadowRay& r : records) EXPECT_TRUE(gpu::host_ray_visible(r));
  // A real segment through the box: the floor's centre seen from far below is blocked.
  std::vector<gpu::HostShadowRay> through{
      gpu::host_ray_segment(glm::vec3(0.0f, -100.0f, 0.0f), glm::vec3(0.0f, 100.0f, 0.0f), 0)};
  ASSERT_TRUE(gpu::host_ray_traced(through[0]));
  host.trace(through);
  EXPECT_TRUE(gpu::host_ray_traced(through[0])) << "Embree keeps the record's id";
  EXPECT_FALSE(gpu::host_ray_visible(through[0]));
}

TEST_F(HostVisibilityTest, ClosestRecordsWithoutARayMiss) {
  const Level level = load_level_argument("cornell_lights");
  const SceneData data = build_scene_data(level);
  const HostVisibility host(device, data.bvh, bvh_instance_descs(level));
  // Slots the pass asked nothing of, non-finite rays and empty ranges (the emit variant's
  // records for them) stay inactive and read as misses, as the BVH answers them.
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  const glm::vec3 up(0.0f, 1.0f, 0.0f);
  const glm::vec3 below(0.0f, -100.0f, 0.0f);
  std::vector<gpu::HostClosestRay> records(300, gpu::host_closest_none());
  records.push_back(gpu::host_closest_ray(glm::vec3(nan), up, gpu::kBvhMiss, 1));
  records.push_back(gpu::host_closest_ray(below, glm::vec3(0.0f, inf, 0.0f), gpu::kBvhMiss, 2));
  records.push_back(gpu::host_closest_ray(below, up, 0.0f, 3));
  records.push_back(gpu::host_closest_ray(below, up, nan, 4));
  // The emit variant writes only the ray: whatever a record's hit held before is reset.
  records[5].instance = 0;
  records[5].primitive = 0;
  records[5].instance_id = 0;
  for (const gpu::HostClosestRay& r : records) {
    EXPECT_FALSE(gpu::host_ray_active(r.ray)) << "record " << r.ray.id << " holds an active ray";
  }
  EXPECT_EQ(host.trace_closest(records), 0u);
  for (const gpu::HostClosestRay& r : records) EXPECT_FALSE(gpu::host_closest_found(r));
  // A real ray into the box from far below meets its floor: an instance, a triangle, t > 0.
  std::vector<gpu::HostClosestRay> through{gpu::host_closest_ray(below, up, gpu::kBvhMiss, 7)};
  EXPECT_EQ(host.trace_closest(through), 1u);
  ASSERT_TRUE(gpu::host_closest_found(through[0]));
  EXPECT_LT(through[0].instance, level.instances.size());
  EXPECT_GT(through[0].ray.tfar, 0.0f);
  EXPECT_LT(through[0].ray.tfar, 200.0f);
  EXPECT_EQ(through[0].ray.id, 7u) << "Embree keeps the record's id";
}

TEST_F(HostVisibilityTest, RefusesAlphaTestedLevelsByName) {
  std::vector<BvhInstanceDesc> descs(2);
  descs[1].flags = gpu::kBvhInstanceAlphaTested;
  EXPECT_TRUE(HostVisibility::supports(std::span(descs).first(1)));
  EXPECT_FALSE(HostVisibility::supports(descs));
  const Level level = load_level_argument("cornell_lights");
  const SceneData data = build_scene_data(level);
  std::vector<BvhInstanceDesc> cut = bvh_instance_descs(level);
  cut.front().flags |= gpu::kBvhInstanceAlphaTested;
  try {
    const HostVisibility host(device, data.bvh, cut);
    FAIL() << "an alpha-tested instance was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("alpha-tested"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace lantern::lighting::test
