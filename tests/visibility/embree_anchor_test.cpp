// visibility_bench's measuring tools answer like the project's CPU traversal on night_market at
// 160x90 (primary rays, the probe's power-sampled shadow rays, and the ReSTIR-like RIS shadow
// rays): Embree flat and two-level agree on >= 99.9% of rays (hit/miss; the bar for every
// visibility path), and the traversal counter's hit/miss equals SceneBvh's on every ray (its
// counts belong to the same traversal).
#include "tests/visibility/embree_anchor.h"

#include <gtest/gtest.h>

#include "engine/level/level_loader.h"
#include "lighting/scene/scene_data.h"
#include "tests/visibility/shading_ray_sets.h"
#include "tests/visibility/traversal_counter.h"
#include "tests/visibility/visibility_harness.h"

namespace lantern::lighting::test {
namespace {

struct Fixture {
  Level level = load_level_argument("night_market");
  SceneData data = build_scene_data(level);
  std::vector<gpu::BvhRay> primary = camera_rays(level.camera, 160, 90);
};

const Fixture& fixture() {
  static const Fixture f;
  return f;
}

void expect_agreement(std::span<const gpu::BvhRay> rays, std::uint32_t mode) {
  const Fixture& f = fixture();
  ASSERT_GT(rays.size(), 1000u);
  const std::vector<glm::uvec4> cpu = cpu_probe(f.data.bvh, rays, mode);
  for (const EmbreeLayout layout : {EmbreeLayout::Flat, EmbreeLayout::TwoLevel}) {
    const EmbreeAnchor anchor(f.level, layout, 2);
    const double agreement = probe_agreement(anchor.run(rays, mode), cpu, mode);
    EXPECT_GE(agreement, 0.999) << embree_layout_name(layout) << " mode " << mode;
  }
  TraversalCounts counts;
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const bool cpu_hit = mode == 0 ? cpu[i].x != ~0u : cpu[i].w == 0u;
    ASSERT_EQ(count_traversal(f.data.bvh, rays[i], mode, counts), cpu_hit) << "ray " << i;
  }
  EXPECT_GT(counts.blas_nodes, counts.rays);  // the counts are not empty
}

TEST(EmbreeAnchor, PrimaryRaysAgreeWithTheCpuTraversal) {
  expect_agreement(fixture().primary, 0);
}

TEST(EmbreeAnchor, ProbeShadowRaysAgreeWithTheCpuTraversal) {
  const Fixture& f = fixture();
  expect_agreement(shadow_rays(f.data.bvh, f.primary, f.data.lights, f.data.scene_radius(), {}, 7),
                   1);
}

TEST(EmbreeAnchor, RisShadowRaysAgreeWithTheCpuTraversal) {
  const Fixture& f = fixture();
  const ShadingRaySet set = shading_shadow_rays(f.level, f.data, f.primary, 8, 9);
  EXPECT_GT(set.surface_points, set.rays.size() / 2);
  expect_agreement(set.rays, 1);
}

TEST(EmbreeAnchor, ReportsItsVersionAndBuildTime) {
  const EmbreeAnchor anchor(fixture().level, EmbreeLayout::Flat, 1);
  EXPECT_EQ(anchor.version().rfind("3.", 0), 0u) << anchor.version();
  EXPECT_GT(anchor.build_ms(), 0.0);
}

}  // namespace
}  // namespace lantern::lighting::test
