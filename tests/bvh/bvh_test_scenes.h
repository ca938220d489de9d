// Test scenes and the brute-force reference for the BVH tests: random triangle soups, a grid mesh,
// random rays, and closest hit over every triangle of every instance.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <random>
#include <vector>

#include "lighting/bvh/scene_bvh.h"

namespace lantern::lighting::test {

struct TestMesh {
  std::vector<glm::vec3> positions;
  std::vector<std::uint32_t> indices;
};

// `count` triangles with vertices near random centres in [-extent, extent]^3, edges up to `size`.
inline TestMesh random_soup(std::uint32_t count, float extent, float size, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> centre(-extent, extent);
  std::uniform_real_distribution<float> offset(-size, size);
  TestMesh mesh;
  for (std::uint32_t t = 0; t < count; ++t) {
    glm::vec3 c(centre(rng), centre(rng), centre(rng));
    for (int v = 0; v < 3; ++v) {
      mesh.indices.push_back(static_cast<std::uint32_t>(mesh.positions.size()));
      mesh.positions.push_back(c + glm::vec3(offset(rng), offset(rng), offset(rng)));
    }
  }
  return mesh;
}

// A height-field grid of n x n quads (2 triangles each) over [-1, 1]^2 in xz, sharing vertices.
inline TestMesh grid_mesh(std::uint32_t n, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> height(-0.05f, 0.05f);
  TestMesh mesh;
  for (std::uint32_t z = 0; z <= n; ++z)
    for (std::uint32_t x = 0; x <= n; ++x)
      mesh.positions.emplace_back(-1.0f + 2.0f * static_cast<float>(x) / static_cast<float>(n),
                                  height(rng),
                                  -1.0f + 2.0f * static_cast<float>(z) / static_cast<float>(n));
  for (std::uint32_t z = 0; z < n; ++z)
    for (std::uint32_t x = 0; x < n; ++x) {
      std::uint32_t a = z * (n + 1) + x, b = a + 1, c = a + n + 1, d = c + 1;
      mesh.indices.insert(mesh.indices.end(), {a, c, b, b, c, d});
    }
  return mesh;
}

inline glm::vec3 random_direction(std::mt19937& rng) {
  std::normal_distribution<float> n(0.0f, 1.0f);
  glm::vec3 d(n(rng), n(rng), n(rng));
  return glm::normalize(d);
}

// Rays from random points in [-extent, extent]^3 in random directions, unbounded.
inline std::vector<gpu::BvhRay> random_rays(std::uint32_t count, float extent, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> pos(-extent, extent);
  std::vector<gpu::BvhRay> rays;
  for (std::uint32_t i = 0; i < count; ++i)
    rays.push_back(gpu::bvh_make_ray(glm::vec3(pos(rng), pos(rng), pos(rng)), random_direction(rng),
                                     0.0f, gpu::kBvhMiss));
  return rays;
}

// One mesh placed with a transform, for the brute-force reference.
struct PlacedMesh {
  const TestMesh* mesh;
  glm::mat4 world_to_object;
};

// Closest hit over every triangle of every placed mesh, testing in object space with the same
// transform and triangle test as the traversal, so results must match it exactly.
inline bool brute_force_closest(const std::vector<PlacedMesh>& scene, const gpu::BvhRay& ray,
                                gpu::BvhHit& hit) {
  hit = gpu::BvhHit{};
  hit.t = ray.direction.w;
  bool found = false;
  for (std::size_t i = 0; i < scene.size(); ++i) {
    const TestMesh& m = *scene[i].mesh;
    glm::vec3 o = glm::vec3(scene[i].world_to_object * glm::vec4(glm::vec3(ray.origin), 1.0f));
    glm::vec3 d = glm::vec3(scene[i].world_to_object * glm::vec4(glm::vec3(ray.direction), 0.0f));
    for (std::size_t t = 0; t < m.indices.size() / 3; ++t) {
      glm::vec3 v0 = m.positions[m.indices[3 * t]];
      gpu::BvhTriangle tri;
      tri.v0 = glm::vec4(v0, 0.0f);
      tri.e1 = glm::vec4(m.positions[m.indices[3 * t + 1]] - v0, 0.0f);
      tri.e2 = glm::vec4(m.positions[m.indices[3 * t + 2]] - v0, 0.0f);
      glm::vec3 tuv;
      if (gpu::bvh_ray_triangle(o, d, tri, ray.origin.w, hit.t, tuv)) {
        hit.t = tuv.x;
        hit.u = tuv.y;
        hit.v = tuv.z;
        hit.instance = static_cast<std::uint32_t>(i);
        hit.primitive = static_cast<std::uint32_t>(t);
        found = true;
      }
    }
  }
  return found;
}

// A scene of one mesh placed once with the identity transform.
inline SceneBvh single_mesh_scene(const TestMesh& mesh, const BvhBuildOptions& options = {}) {
  SceneBvh scene;
  std::uint32_t id = scene.add_mesh(MeshBvh(mesh.positions, mesh.indices, options));
  BvhInstanceDesc inst;
  inst.mesh = id;
  scene.set_instances({&inst, 1});
  return scene;
}

}  // namespace lantern::lighting::test
