// Visibility backends agree (shaders/lib/visibility.glsl): primary rays per pixel at 160x90 and
// shadow rays towards lights, traced by the compute BVH on the GPU (texel-buffer and storage-buffer
// fetches), VK_KHR_ray_query on the GPU and the CPU traversal (SceneBvh). Hit/miss + instance id
// (primary) and visible/blocked (shadow) agree for >= 99.9% of rays; zero validation errors.
// Scenes: cornell_lights, and a generated one with 48 rotated/scaled instances of three meshes
// whose TLAS is rebuilt for a second frame with every instance moved.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "engine/core/error.h"
#include "engine/level/level_loader.h"
#include "lighting/scene/scene_data.h"
#include "tests/bvh/bvh_test_scenes.h"
#include "tests/runtime/gpu_test_support.h"
#include "tests/visibility/visibility_harness.h"

namespace lantern::lighting {
namespace {

constexpr std::uint32_t kWidth = 160;
constexpr std::uint32_t kHeight = 90;
constexpr double kMinAgreement = 0.999;

struct Agreement {
  std::size_t rays = 0;
  std::size_t hit_miss = 0;   // primary: same hit/miss; shadow: same visible/blocked
  std::size_t instance = 0;   // primary: same hit/miss and, on a hit, the same instance
  std::size_t primitive = 0;  // primary: ... and the same primitive
  double fraction(std::size_t n) const { return rays == 0 ? 1.0 : double(n) / double(rays); }
};

Agreement compare(const std::vector<glm::uvec4>& a, const std::vector<glm::uvec4>& b,
                  std::uint32_t mode) {
  Agreement g;
  g.rays = a.size();
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (mode == 1) {
      g.hit_miss += a[i].w == b[i].w;
      continue;
    }
    const bool hit_a = a[i].x != ~0u, hit_b = b[i].x != ~0u;
    g.hit_miss += hit_a == hit_b;
    g.instance += hit_a == hit_b && a[i].x == b[i].x;
    g.primitive += hit_a == hit_b && a[i].x == b[i].x && a[i].y == b[i].y;
  }
  return g;
}

class VisibilityGpuTest : public runtime::test::GpuTest {
 protected:
  // Traces primary and shadow rays with every backend and checks agreement with the CPU.
  void check_all_backends(const std::vector<VisibilityScene*>& scenes, const SceneBvh& bvh,
                          const std::vector<gpu::BvhRay>& primary,
                          const std::vector<gpu::BvhRay>& shadow, const char* what) {
    const std::vector<glm::uvec4> cpu_primary = test::cpu_probe(bvh, primary, 0);
    const std::vector<glm::uvec4> cpu_shadow = test::cpu_probe(bvh, shadow, 1);
    std::size_t hits = 0, blocked = 0;
    for (const auto& r : cpu_primary) hits += r.x != ~0u;
    for (const auto& r : cpu_shadow) blocked += r.w == 0u;
    // The scenes must exercise both outcomes, or agreement would be trivial.
    EXPECT_GT(hits, primary.size() / 8) << what;
    EXPECT_LT(hits, primary.size()) << what;
    EXPECT_GT(blocked, shadow.size() / 50) << what;
    EXPECT_LT(blocked, shadow.size() - shadow.size() / 50) << what;
    for (VisibilityScene* scene : scenes) {
      for (std::string_view variant : variants(scene->backend())) {
        test::Probe probe(device, shaders, variant);
        const Agreement p = compare(probe.run(*scene, primary, 0), cpu_primary, 0);
        const Agreement s = compare(probe.run(*scene, shadow, 1), cpu_shadow, 1);
        const std::string label = fmt::format("{} variant '{}' ({} primary, {} shadow rays)", what,
                                              variant, p.rays, s.rays);
        EXPECT_GE(p.fraction(p.hit_miss), kMinAgreement) << label;
        EXPECT_GE(p.fraction(p.instance), kMinAgreement) << label;
        EXPECT_GE(p.fraction(p.primitive), 0.99) << label;
        EXPECT_GE(s.fraction(s.hit_miss), kMinAgreement) << label;
        RecordProperty(
            fmt::format("{}_{}_primary_mismatch", what, variant.empty() ? "texel" : variant),
            static_cast<int>(p.rays - p.instance));
        RecordProperty(
            fmt::format("{}_{}_shadow_mismatch", what, variant.empty() ? "texel" : variant),
            static_cast<int>(s.rays - s.hit_miss));
      }
    }
  }

  static std::vector<std::string_view> variants(VisibilityBackend backend) {
    if (backend == VisibilityBackend::RayQuery) return {visibility_variant(backend)};
    return {visibility_variant(backend), "storage"};
  }

  runtime::ShaderLibrary shaders;
};

TEST_F(VisibilityGpuTest, CornellLightsBackendsAgreeWithTheCpu) {
  ASSERT_TRUE(device.caps().ray_query) << "lavapipe 25 has VK_KHR_ray_query (PLATFORM.md)";
  const Level level = load_level_argument("cornell_lights");
  const SceneData data = build_scene_data(level);
  VisibilityScene bvh_scene(device, data.bvh, VisibilityBackend::Bvh);
  VisibilityScene rq_scene(device, data.bvh, VisibilityBackend::RayQuery);
  EXPECT_EQ(rq_scene.backend(), VisibilityBackend::RayQuery);

  const std::vector<gpu::BvhRay> primary = test::camera_rays(level.camera, kWidth, kHeight);
  const std::vector<gpu::BvhRay> shadow =
      test::shadow_rays(data.bvh, primary, data.lights, data.scene_radius(), {}, 7);
  check_all_backends({&bvh_scene, &rq_scene}, data.bvh, primary, shadow, "cornell_lights");
}

TEST_F(VisibilityGpuTest, InstancedSceneAgreesBeforeAndAfterATlasRebuild) {
  const std::vector<test::TestMesh> meshes = {test::random_soup(300, 1.0f, 0.35f, 1),
                                              test::grid_mesh(10, 2),
                                              test::random_soup(150, 0.5f, 0.25f, 3)};
  SceneBvh bvh;
  for (const test::TestMesh& m : meshes) bvh.add_mesh(MeshBvh(m.positions, m.indices));
  // Every other instance is fixed (merged into the world-space tree) and keeps its place; the
  // others move with the seed.
  std::vector<BvhInstanceDesc> descs;
  auto place = [&](std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> pos(-6.0f, 6.0f), scale(0.5f, 2.0f), angle(0.0f, 6.28f);
    const bool first = descs.empty();
    descs.resize(48);
    for (std::uint32_t i = 0; i < 48; ++i) {
      glm::mat4 m = glm::translate(glm::mat4(1.0f), glm::vec3(pos(rng), pos(rng), pos(rng)));
      m = glm::rotate(m, angle(rng), test::random_direction(rng));
      m = glm::scale(m, glm::vec3(scale(rng), scale(rng), scale(rng)));
      const bool fixed = i % 2 == 0;
      if (first || !fixed)
        descs[i] = {.mesh = i % 3, .object_to_world = m, .user_id = 100 + i, .fixed = fixed};
    }
    bvh.set_instances(descs);
  };
  place(11);
  EXPECT_EQ(bvh.merged_instance_count(), 24u);
  VisibilityScene bvh_scene(device, bvh, VisibilityBackend::Bvh);
  VisibilityScene rq_scene(device, bvh, VisibilityBackend::RayQuery);

  Camera camera;
  camera.position = glm::vec3(1.0f, 4.0f, 20.0f);
  camera.orientation = look_at_orientation(camera.position, glm::vec3(0.0f));
  camera.yfov = 0.9f;
  const std::vector<gpu::BvhRay> primary = test::camera_rays(camera, kWidth, kHeight);
  // Shadow rays from every primary hit to points around and inside the cluster.
  auto shadow_to_points = [&](const std::vector<glm::vec3>& points) {
    std::vector<gpu::BvhRay> rays;
    for (const gpu::BvhRay& ray : primary) {
      gpu::BvhHit hit;
      if (!bvh.trace_closest(ray, hit)) continue;
      const glm::vec3 p = glm::vec3(ray.origin) + hit.t * glm::vec3(ray.direction);
      const glm::vec3 target = points[rays.size() % points.size()];
      rays.push_back(gpu::bvh_make_ray(p, target - p, 0.0f, 1.0f));
    }
    return rays;
  };
  const std::vector<glm::vec3> points = {
      {0.0f, 12.0f, 0.0f}, {9.0f, 3.0f, 9.0f}, {-8.0f, -2.0f, 6.0f}, {0.5f, 0.5f, 0.5f}};
  check_all_backends({&bvh_scene, &rq_scene}, bvh, primary, shadow_to_points(points), "frame0");

  place(12);  // the instanced half moves: TLAS rebuilt on both backends
  EXPECT_EQ(bvh.merged_instance_count(), 24u);
  bvh_scene.update(bvh);
  rq_scene.update(bvh);
  check_all_backends({&bvh_scene, &rq_scene}, bvh, primary, shadow_to_points(points), "frame1");
}

TEST_F(VisibilityGpuTest, BindRefusesARayQueryShaderOnTheBvhBackend) {
  SceneBvh bvh = test::single_mesh_scene(test::grid_mesh(2, 1));
  VisibilityScene scene(device, bvh, VisibilityBackend::Bvh);
  runtime::ComputePipeline pipeline(device, shaders.load("tests/visibility_probe.comp", "rayquery"),
                                    {.name = "visibility.probe"});
  runtime::Bindings bindings(pipeline);
  EXPECT_THROW(scene.bind(bindings), RuntimeError);
}

}  // namespace
}  // namespace lantern::lighting
