// The gbuffer passes on lavapipe against the CPU: at 160x90 on cornell_lights, instance ids,
// world positions, view depth, normals, materials and emission agree with SceneBvh::trace_closest
// of the same pixel-centre camera rays (baseline.comp's construction) for >= 99.9% of pixels;
// motion vectors equal the analytic reprojection through prev_view_proj (moving camera) and
// prev_object_to_world (moving instance) within 0.01 px; sky pixels are position.w == 0 and
// ids.x == kNoInstance; nothing is NaN; validation stays silent. The default (visibility: cull,
// raster ids, resolve) method is the one tested; on night_market (147k small triangles, where the
// cull drops most of them) it also agrees with the CPU trace and with the forward method (no
// culling, every attribute interpolated by the raster).
#include "shared/gbuffer.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <unistd.h>

#include "engine/level/level_loader.h"
#include "lighting/scene/frame_constants.h"
#include "lighting/scene/scene_data.h"
#include "runtime/gpu/shader_library.h"
#include "tests/gbuffer/gbuffer_harness.h"
#include "tests/runtime/gpu_test_support.h"

namespace lantern {
namespace {

constexpr std::uint32_t kWidth = 160;
constexpr std::uint32_t kHeight = 90;

class GBufferTest : public runtime::test::GpuTest {
 protected:
  runtime::ShaderLibrary shaders;
};

// The cornell_lights tests run for both methods (Auto would pick Forward for its 122 triangles).
class GBufferMethodTest : public GBufferTest,
                          public ::testing::WithParamInterface<lighting::GBufferMethod> {
 protected:
  lighting::GBufferPassOptions options() const { return {.method = GetParam()}; }
};

bool finite(const glm::vec4& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z) && std::isfinite(v.w);
}

std::size_t count_non_finite(const test::GBufferImages& g) {
  std::size_t bad = 0;
  for (const auto* image :
       {&g.position, &g.normal, &g.albedo_roughness, &g.emission_metallic, &g.motion}) {
    for (const glm::vec4& v : *image) bad += finite(v) ? 0 : 1;
  }
  return bad;
}

// Camera ray through image position (x, y) in pixels (baseline.comp shade_pixel).
gpu::BvhRay camera_ray(const gpu::FrameConstants& fc, float x, float y) {
  const glm::vec2 ndc =
      glm::vec2(x / static_cast<float>(fc.frame.x), y / static_cast<float>(fc.frame.y)) * 2.0f -
      1.0f;
  const glm::vec4 a = fc.inv_view_proj * glm::vec4(ndc, 0.0f, 1.0f);
  const glm::vec4 b = fc.inv_view_proj * glm::vec4(ndc, 0.5f, 1.0f);
  const glm::vec3 dir = glm::normalize(glm::vec3(b) / b.w - glm::vec3(a) / a.w);
  return gpu::bvh_make_ray(glm::vec3(fc.camera_position), dir, 0.0f, gpu::kBvhMiss);
}

// Pixel position (x right, y down, pixel centres at half-integers) of world point p.
glm::vec2 project(const glm::mat4& view_proj, const glm::vec3& p, glm::uvec2 size) {
  const glm::vec4 clip = view_proj * glm::vec4(p, 1.0f);
  return (glm::vec2(clip) / clip.w * 0.5f + 0.5f) * glm::vec2(size);
}

// World-space front normal of triangle `t` of instance `i` (winding, mirrored by det < 0).
glm::vec3 front_normal(const lighting::SceneData& scene, std::uint32_t i, std::uint32_t t) {
  const gpu::GpuInstance& inst = scene.instances[i];
  glm::vec3 p[3];
  for (std::uint32_t k = 0; k < 3; ++k) {
    const std::uint32_t index = scene.indices[inst.geometry.y + 3 * t + k];
    p[k] =
        glm::vec3(inst.object_to_world *
                  glm::vec4(glm::vec3(scene.vertices[inst.geometry.w + index].position_u), 1.0f));
  }
  const glm::vec3 n = glm::normalize(glm::cross(p[1] - p[0], p[2] - p[0]));
  return glm::determinant(glm::mat3(inst.object_to_world)) < 0.0f ? -n : n;
}

// True when `ray` meets triangle `t` of instance `i` with barycentrics inside [-1e-4, 1 + 1e-4]
// at a distance no greater than (1 + 1e-4) * t_max.
bool touches_triangle(const lighting::SceneData& scene, std::uint32_t i, std::uint32_t t,
                      const gpu::BvhRay& ray, float t_max) {
  const gpu::GpuInstance& inst = scene.instances[i];
  if (3 * t + 2 >= inst.geometry.z) return false;
  glm::dvec3 p[3];
  for (std::uint32_t k = 0; k < 3; ++k) {
    const std::uint32_t index = scene.indices[inst.geometry.y + 3 * t + k];
    p[k] =
        glm::dvec3(inst.object_to_world *
                   glm::vec4(glm::vec3(scene.vertices[inst.geometry.w + index].position_u), 1.0f));
  }
  const glm::dvec3 o(ray.origin), d(ray.direction);
  const glm::dvec3 e1 = p[1] - p[0], e2 = p[2] - p[0];
  const glm::dvec3 q = glm::cross(d, e2);
  const double det = glm::dot(e1, q);
  if (std::abs(det) < 1e-20) return false;
  const glm::dvec3 s = o - p[0];
  const double u = glm::dot(s, q) / det;
  const glm::dvec3 r = glm::cross(s, e1);
  const double v = glm::dot(d, r) / det;
  const double dist = glm::dot(e2, r) / det;
  constexpr double kEps = 1e-4;
  return u >= -kEps && v >= -kEps && u + v <= 1.0 + kEps && dist > 0.0 &&
         dist <= (1.0 + kEps) * static_cast<double>(t_max);
}

gpu::FrameConstants constants_for(const Camera& camera) {
  return lighting::make_frame_constants(camera, kWidth, kHeight, 0, 1, {});
}

// constants_for(camera) after a camera that stood a few centimetres away last frame (every pixel
// has motion).
gpu::FrameConstants moving_constants_for(const Camera& camera) {
  gpu::FrameConstants fc = constants_for(camera);
  Camera prev = camera;
  prev.position += glm::vec3(0.05f, 0.02f, -0.1f);
  fc.prev_view_proj = lighting::camera_view_proj(prev, kWidth, kHeight);
  return fc;
}

struct Agreement {
  std::size_t pixels = 0, agree = 0, hits = 0, sky = 0, front_emitters = 0;
  std::size_t back_emitters = 0;  // emissive material seen from behind (must show no emission)
  std::size_t edges = 0;  // ids differ, but the ray passes (within rounding) through both hits
  std::size_t attribute_mismatches = 0;  // normals, depth, material, emission on agreeing hits
  std::string first_problem;
};

// Compares every pixel of `g` with the CPU trace of the pixel-centre ray.
Agreement compare_with_cpu(const lighting::SceneData& scene, const gpu::FrameConstants& fc,
                           const test::GBufferImages& g) {
  Agreement a;
  auto problem = [&](std::uint32_t x, std::uint32_t y, const std::string& what) {
    if (a.first_problem.empty()) a.first_problem = fmt::format("pixel ({}, {}): {}", x, y, what);
  };
  for (std::uint32_t y = 0; y < g.height; ++y) {
    for (std::uint32_t x = 0; x < g.width; ++x) {
      ++a.pixels;
      const std::size_t i = g.index(x, y);
      const gpu::BvhRay ray =
          camera_ray(fc, static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f);
      gpu::BvhHit hit{};
      const bool cpu_hit = scene.bvh.trace_closest(ray, hit);
      const bool gpu_sky = gpu::gbuffer_is_sky(g.position[i].w);
      if (!cpu_hit) {
        if (gpu_sky && g.ids[i].x == gpu::kNoInstance) {
          ++a.agree;
          ++a.sky;
        } else {
          problem(x, y, fmt::format("CPU misses, GPU instance {}", g.ids[i].x));
        }
        continue;
      }
      const glm::vec3 dir(ray.direction);
      const glm::vec3 cpu_p = glm::vec3(ray.origin) + hit.t * dir;
      const glm::vec3 gpu_p(g.position[i]);
      const bool same_surface = !gpu_sky && g.ids[i].x == hit.instance &&
                                g.ids[i].z == hit.primitive &&
                                glm::length(gpu_p - cpu_p) <= 1e-3f * hit.t;
      if (!same_surface) {
        // An edge: the centre lies (within rounding) on the GPU's triangle too, no farther than
        // the CPU's hit (shared edges, corners where surfaces meet, edges of decals).
        if (!gpu_sky && g.ids[i].x < scene.instances.size() &&
            touches_triangle(scene, g.ids[i].x, g.ids[i].z, ray, hit.t)) {
          ++a.edges;
          continue;
        }
        problem(x, y,
                fmt::format("CPU instance {} triangle {} at t {}, GPU instance {} "
                            "triangle {} at distance {}",
                            hit.instance, hit.primitive, hit.t, g.ids[i].x, g.ids[i].z,
                            glm::length(gpu_p - cpu_p)));
        continue;
      }
      ++a.agree;
      ++a.hits;
      // Attributes of the agreeing hit.
      const gpu::GpuInstance& inst = scene.instances[hit.instance];
      const glm::vec3 front = front_normal(scene, hit.instance, hit.primitive);
      const bool sees_front = glm::dot(front, -dir) > 0.0f;
      const glm::vec3 facing = sees_front ? front : -front;
      const glm::vec3 ng = gpu::oct_decode(glm::vec2(g.normal[i].z, g.normal[i].w));
      const glm::vec3 ns = gpu::oct_decode(glm::vec2(g.normal[i].x, g.normal[i].y));
      const float depth = (fc.view_proj * glm::vec4(cpu_p, 1.0f)).w;
      const gpu::GpuMaterial& m = scene.materials[inst.geometry.x];
      const glm::vec3 emission = sees_front ? glm::vec3(m.emission) : glm::vec3(0.0f);
      const glm::vec3 gpu_emission(g.emission_metallic[i]);
      std::string bad;
      if (g.ids[i].y != inst.geometry.x) bad += " material";
      if (glm::dot(ng, facing) < 0.999f && std::abs(glm::dot(front, dir)) > 1e-3f)
        bad += " geometric-normal";
      if (glm::dot(ns, ng) < -1e-6f) bad += " shading-normal";
      if (std::abs(g.position[i].w - depth) > 1e-3f * depth) bad += " depth";
      if (glm::length(gpu_emission - emission) > 1e-6f * glm::length(emission) + 1e-12f)
        bad += " emission";
      if (std::abs(g.emission_metallic[i].w - m.params.y) > 1e-6f) bad += " metallic";
      if (glm::length(glm::vec3(g.albedo_roughness[i]) - glm::vec3(m.base_color)) > 2e-3f ||
          std::abs(g.albedo_roughness[i].w - m.params.x) > 2e-3f)
        bad += " albedo/roughness";
      if (!bad.empty()) {
        ++a.attribute_mismatches;
        problem(x, y, "attributes differ:" + bad);
      }
      if (glm::length(glm::vec3(m.emission)) > 0.0f)
        ++(sees_front ? a.front_emitters : a.back_emitters);
    }
  }
  return a;
}

// >= 99.9% of the pixels that are not edges agree, and edges are few (a broken pass cannot
// hide behind them).
void expect_agreement(const Agreement& a, const char* what) {
  const std::size_t judged = a.pixels - a.edges;
  EXPECT_GE(static_cast<double>(a.agree), 0.999 * static_cast<double>(judged))
      << what << ": " << judged - a.agree << " of " << judged
      << " pixels disagree; first: " << a.first_problem;
  EXPECT_LE(static_cast<double>(a.edges), 0.01 * static_cast<double>(a.pixels)) << what;
  ::testing::Test::RecordProperty(std::string(what) + " edge pixels", std::to_string(a.edges));
  ::testing::Test::RecordProperty(std::string(what) + " disagreeing pixels",
                                  std::to_string(judged - a.agree));
  EXPECT_LE(static_cast<double>(a.attribute_mismatches), 0.001 * static_cast<double>(a.pixels))
      << what << ": first: " << a.first_problem;
}

TEST_P(GBufferMethodTest, CornellLightsAgreesWithCpuTrace) {
  const Level level = load_level_argument("cornell_lights");
  const lighting::SceneData scene = lighting::build_scene_data(level);
  test::GBufferHarness harness(device, shaders, scene, options());
  harness.warm_up();
  const gpu::FrameConstants fc = constants_for(level.camera);
  const test::GBufferImages g = *harness.render(fc, true);
  EXPECT_EQ(count_non_finite(g), 0u);
  const Agreement a = compare_with_cpu(scene, fc, g);
  expect_agreement(a, "cornell_lights");
  EXPECT_GT(a.hits, a.pixels / 2) << "the camera should mostly see geometry";
  EXPECT_GT(a.front_emitters, 10u) << "too few emitter pixels: emission is untested";
  // Static camera and instances: no motion, exactly (gbuffer_point_motion). The ~1e-4 px a
  // hit re-projected against its pixel centre used to give is a bilinear history weight that
  // carries a lit neighbour's second moment into a black pixel's variance in the denoiser.
  std::size_t moving = 0;
  for (const glm::vec4& m : g.motion) moving += glm::vec2(m) != glm::vec2(0.0f);
  EXPECT_EQ(moving, 0u) << "pixels with nonzero motion in a still frame";
  // The method's first pass ran (the host method's is the host pass gbuffer.host).
  EXPECT_GT(harness.last_ms(GetParam() == lighting::GBufferMethod::Host ? "gbuffer.host"
                                                                         : "gbuffer"),
            0.0);
}

// Seen from outside and above with the ceiling removed: sky around the box, the ceiling panels
// from behind (no emission), and one instance mirrored (negative determinant: winding flips).
TEST_P(GBufferMethodTest, SkyBackFacesAndMirroredInstanceAgreeWithCpuTrace) {
  Level level = load_level_argument("cornell_lights");
  const auto ceiling = std::find_if(level.instances.begin(), level.instances.end(),
                                    [](const Instance& i) { return i.name == "ceiling"; });
  ASSERT_NE(ceiling, level.instances.end());
  level.instances.erase(ceiling);
  std::uint32_t mirrored = 0;  // the smallest instance: a box, not a wall
  for (std::uint32_t i = 0; i < level.instances.size(); ++i) {
    if (level.meshes[level.instances[i].mesh].indices.size() <
        level.meshes[level.instances[mirrored].mesh].indices.size()) {
      mirrored = i;
    }
  }
  level.instances[mirrored].world =
      level.instances[mirrored].world * glm::scale(glm::mat4(1.0f), glm::vec3(-1.0f, 1.0f, 1.0f));
  level.camera.position = glm::vec3(-1.5f, 2.5f, 7.0f);
  level.camera.orientation =
      look_at_orientation(level.camera.position, glm::vec3(0.5f, 1.0f, 0.0f));
  const lighting::SceneData scene = lighting::build_scene_data(level);
  ASSERT_LT(glm::determinant(glm::mat3(scene.instances[mirrored].object_to_world)), 0.0f)
      << "the mirrored transform did not reach the scene records";
  test::GBufferHarness harness(device, shaders, scene, options());
  const gpu::FrameConstants fc = constants_for(level.camera);
  const test::GBufferImages g = *harness.render(fc, true);
  EXPECT_EQ(count_non_finite(g), 0u);
  const Agreement a = compare_with_cpu(scene, fc, g);
  expect_agreement(a, "outside view");
  EXPECT_GT(a.sky, a.pixels / 10) << "the view should show sky";
  EXPECT_GT(a.back_emitters, 10u) << "the ceiling panels should be seen from behind";
  EXPECT_GT(a.hits, a.pixels / 10);
  std::size_t mirrored_pixels = 0;
  for (std::size_t i = 0; i < g.ids.size(); ++i) {
    if (gpu::gbuffer_is_sky(g.position[i].w)) {
      EXPECT_EQ(g.position[i].w, 0.0f);
      EXPECT_EQ(g.ids[i].x, gpu::kNoInstance);
      EXPECT_EQ(g.motion[i], glm::vec4(0.0f));
    }
    mirrored_pixels += g.ids[i].x == mirrored ? 1 : 0;
  }
  EXPECT_GT(mirrored_pixels, 20u) << "the mirrored instance is barely visible";
}

TEST_P(GBufferMethodTest, CameraMotionIsTheReprojectionThroughPrevViewProj) {
  const Level level = load_level_argument("cornell_lights");
  const lighting::SceneData scene = lighting::build_scene_data(level);
  test::GBufferHarness harness(device, shaders, scene, options());
  Camera prev = level.camera;
  prev.position += glm::vec3(0.12f, -0.07f, 0.15f);
  prev.orientation = glm::angleAxis(glm::radians(2.5f), glm::vec3(0.0f, 1.0f, 0.0f)) *
                     glm::angleAxis(glm::radians(-1.5f), glm::vec3(1.0f, 0.0f, 0.0f)) *
                     prev.orientation;
  gpu::FrameConstants fc = constants_for(level.camera);
  fc.prev_view_proj = lighting::camera_view_proj(prev, kWidth, kHeight);
  fc.prev_camera_position = glm::vec4(prev.position, prev.yfov);
  fc.counts.w = 0;
  const test::GBufferImages g = *harness.render(fc, true);
  EXPECT_EQ(count_non_finite(g), 0u);
  expect_agreement(compare_with_cpu(scene, fc, g), "moving camera");

  float max_error = 0.0f, max_motion = 0.0f;
  std::size_t checked = 0;
  for (std::uint32_t y = 0; y < kHeight; ++y) {
    for (std::uint32_t x = 0; x < kWidth; ++x) {
      const std::size_t i = g.index(x, y);
      if (gpu::gbuffer_is_sky(g.position[i].w)) continue;
      const glm::vec2 expected =
          project(fc.prev_view_proj, glm::vec3(g.position[i]), glm::uvec2(kWidth, kHeight)) -
          glm::vec2(static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f);
      const float error = glm::length(glm::vec2(g.motion[i]) - expected);
      EXPECT_LE(error, 0.01f) << "pixel (" << x << ", " << y << ") expected motion (" << expected.x
                              << ", " << expected.y << ") got (" << g.motion[i].x << ", "
                              << g.motion[i].y << ")";
      // Without jitter the point's own motion (zw) is the sampled one (xy), to the bit.
      EXPECT_EQ(glm::vec2(g.motion[i].z, g.motion[i].w), glm::vec2(g.motion[i]));
      if (error > 0.01f) return;  // one report is enough
      max_error = std::max(max_error, error);
      max_motion = std::max(max_motion, glm::length(expected));
      ++checked;
    }
  }
  EXPECT_GT(checked, kWidth * kHeight / 2);
  EXPECT_GT(max_motion, 2.0f) << "the camera barely moved: the test proves nothing";
  RecordProperty("max_motion_error_px", std::to_string(max_error));

  // Jittered (this frame's samples at pixel + 0.5 + j, last frame's at + pj): zw is the point's
  // own motion, from where this frame's sample hit it to where it was last frame; xy leads to
  // the previous frame's pixel whose sample was nearest, so it adds the jitter step j - pj.
  // upscale.temporal moves its unjittered history by zw, restir.temporal and denoise.temporal
  // reproject per-sample history by xy.
  fc.jitter = glm::vec4(0.31f, -0.27f, -0.12f, 0.4f);
  const glm::vec2 jitter(fc.jitter.x, fc.jitter.y), previous_jitter(fc.jitter.z, fc.jitter.w);
  const test::GBufferImages jittered = *harness.render(fc, true);
  EXPECT_EQ(count_non_finite(jittered), 0u);
  std::size_t own_off = 0, sampled_off = 0, surfaces = 0;
  for (std::uint32_t y = 0; y < kHeight; ++y) {
    for (std::uint32_t x = 0; x < kWidth; ++x) {
      const std::size_t i = jittered.index(x, y);
      const glm::vec4 m = jittered.motion[i];
      if (gpu::gbuffer_is_sky(jittered.position[i].w)) {
        EXPECT_EQ(m, glm::vec4(0.0f)) << "sky pixel (" << x << ", " << y << ")";
        continue;
      }
      ++surfaces;
      const glm::vec2 own =
          project(fc.prev_view_proj, glm::vec3(jittered.position[i]), glm::uvec2(kWidth, kHeight)) -
          (glm::vec2(static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f) + jitter);
      own_off += glm::length(glm::vec2(m.z, m.w) - own) > 0.01f;
      sampled_off += glm::length(glm::vec2(m) - (own + jitter - previous_jitter)) > 0.01f;
    }
  }
  EXPECT_GT(surfaces, kWidth * kHeight / 2);
  EXPECT_EQ(own_off, 0u) << "surface pixels whose zw is not the point's own motion";
  EXPECT_EQ(sampled_off, 0u) << "surface pixels whose xy does not lead to last frame's sample";
}

TEST_P(GBufferMethodTest, MovingInstanceGetsItsObjectMotion) {
  const Level level = load_level_argument("cornell_lights");
  const lighting::SceneData scene = lighting::build_scene_data(level);
  test::GBufferHarness harness(device, shaders, scene, options());
  const gpu::FrameConstants fc = constants_for(level.camera);
  const test::GBufferImages still = *harness.render(fc, true);

  // The instance covering the most pixels that is not the biggest mesh (walls are one mesh).
  std::map<std::uint32_t, std::size_t> coverage;
  for (const glm::uvec4& id : still.ids) {
    if (id.x != gpu::kNoInstance) ++coverage[id.x];
  }
  std::uint32_t moving = gpu::kNoInstance;
  std::size_t best = 0;
  for (const auto& [instance, pixels] : coverage) {
    if (pixels > best && pixels < still.ids.size() / 4) {
      moving = instance;
      best = pixels;
    }
  }
  ASSERT_NE(moving, gpu::kNoInstance);
  ASSERT_GT(best, 50u);

  std::vector<gpu::GpuInstance> instances = scene.instances;
  const glm::mat4 delta =
      glm::translate(glm::mat4(1.0f), glm::vec3(0.04f, 0.03f, -0.05f)) *
      glm::rotate(glm::mat4(1.0f), glm::radians(4.0f), glm::normalize(glm::vec3(1.0f, 2.0f, 0.5f)));
  instances[moving].prev_object_to_world = delta * instances[moving].object_to_world;
  harness.set_instances(instances);
  const test::GBufferImages g = *harness.render(fc, true);
  EXPECT_EQ(count_non_finite(g), 0u);

  float max_motion = 0.0f;
  std::size_t moving_pixels = 0;
  for (std::uint32_t y = 0; y < kHeight; ++y) {
    for (std::uint32_t x = 0; x < kWidth; ++x) {
      const std::size_t i = g.index(x, y);
      ASSERT_EQ(g.ids[i], still.ids[i]) << "current geometry must not change";
      glm::vec2 expected(0.0f);
      if (g.ids[i].x == moving) {
        const glm::vec3 prev = glm::vec3(delta * glm::vec4(glm::vec3(g.position[i]), 1.0f));
        expected = project(fc.view_proj, prev, glm::uvec2(kWidth, kHeight)) -
                   glm::vec2(static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f);
        max_motion = std::max(max_motion, glm::length(expected));
        ++moving_pixels;
      }
      const float error = glm::length(glm::vec2(g.motion[i]) - expected);
      ASSERT_LE(error, 0.01f) << "pixel (" << x << ", " << y << ") instance " << g.ids[i].x
                              << " expected (" << expected.x << ", " << expected.y << ") got ("
                              << g.motion[i].x << ", " << g.motion[i].y << ")";
    }
  }
  EXPECT_EQ(moving_pixels, best);
  EXPECT_GT(max_motion, 0.5f) << "the instance barely moved: the test proves nothing";
}

// Dense geometry: most triangles are smaller than a pixel, so gbuffer.cull's pixel-centre test
// decides for most of them; a wrongly culled triangle shows as a pixel the CPU trace disagrees on.
// Both methods that night_market's triangle count picks (visibility on GPUs, host on CPUs).
TEST_F(GBufferTest, NightMarketAgreesWithCpuTrace) {
  const Level level = load_level_argument("night_market");
  const lighting::SceneData scene = lighting::build_scene_data(level);
  for (const lighting::GBufferMethod method :
       {lighting::GBufferMethod::Visibility, lighting::GBufferMethod::Host}) {
    SCOPED_TRACE(std::string(lighting::gbuffer_method_name(method)));
    test::GBufferHarness harness(device, shaders, scene, {.method = method});
    harness.warm_up();
    const gpu::FrameConstants fc = constants_for(level.camera);
    const test::GBufferImages g = *harness.render(fc, true);
    EXPECT_EQ(count_non_finite(g), 0u);
    const Agreement a = compare_with_cpu(scene, fc, g);
    RecordProperty(fmt::format("edges_{}", lighting::gbuffer_method_name(method)),
                   std::to_string(a.edges));
    expect_agreement(a, "night_market");
    EXPECT_GT(a.hits, a.pixels / 2) << "the camera should mostly see geometry";
  }
}

// The two methods rasterise the same triangles with the same rules: the same surface at every
// pixel but where rounding differs (clip positions are computed in a different order), and the
// same attributes there, up to how each interpolates (the forward raster interpolates between
// snapped vertices, the resolve intersects the exact pixel-centre ray: they differ by ~1e-3 on
// grazing triangles and a few hundredths of a pixel in motion; the CPU-trace and analytic-motion
// tests bound the error of each).
TEST_F(GBufferTest, VisibilityMethodMatchesForwardMethod) {
  const Level level = load_level_argument("night_market");
  const lighting::SceneData scene = lighting::build_scene_data(level);
  const gpu::FrameConstants fc = moving_constants_for(level.camera);
  test::GBufferHarness visibility(device, shaders, scene,
                                  {.method = lighting::GBufferMethod::Visibility});
  test::GBufferHarness forward(device, shaders, scene,
                               {.method = lighting::GBufferMethod::Forward});
  const test::GBufferImages v = *visibility.render(fc, true);
  const test::GBufferImages f = *forward.render(fc, true);
  EXPECT_EQ(count_non_finite(v), 0u);
  std::size_t different = 0, compared = 0, mismatches = 0;
  std::string first;
  for (std::size_t i = 0; i < v.ids.size(); ++i) {
    if (v.ids[i] != f.ids[i]) {
      ++different;
      continue;
    }
    if (v.ids[i].x == gpu::kNoInstance) {
      EXPECT_EQ(v.position[i], f.position[i]);
      EXPECT_EQ(v.motion[i], f.motion[i]);
      continue;
    }
    ++compared;
    // Exact: per-triangle values.
    EXPECT_EQ(v.albedo_roughness[i], f.albedo_roughness[i]);
    EXPECT_EQ(v.emission_metallic[i], f.emission_metallic[i]);
    const glm::vec3 vg = gpu::oct_decode(glm::vec2(v.normal[i].z, v.normal[i].w));
    const glm::vec3 fg = gpu::oct_decode(glm::vec2(f.normal[i].z, f.normal[i].w));
    EXPECT_GT(glm::dot(vg, fg), 0.999f) << "geometric normal, pixel " << i;
    // Interpolated values.
    const float depth = f.position[i].w;
    const float position_error = glm::length(glm::vec3(v.position[i] - f.position[i]));
    const float motion_error = glm::length(glm::vec2(v.motion[i] - f.motion[i]));
    const float normal_dot =
        glm::dot(gpu::oct_decode(glm::vec2(v.normal[i])), gpu::oct_decode(glm::vec2(f.normal[i])));
    if (position_error > 1e-3f * depth || std::abs(v.position[i].w - depth) > 1e-3f * depth ||
        motion_error > 0.05f || normal_dot < 0.999f) {
      ++mismatches;
      if (first.empty()) {
        first = fmt::format("pixel {}: position {} (depth {}), motion {} px, normal dot {}", i,
                            position_error, depth, motion_error, normal_dot);
      }
    }
  }
  RecordProperty("different_pixels", std::to_string(different));
  RecordProperty("attribute_mismatches", std::to_string(mismatches));
  EXPECT_LE(different, v.ids.size() / 200) << "more than 0.5% of the pixels see another surface";
  EXPECT_GT(compared, v.ids.size() / 2);
  EXPECT_LE(mismatches, compared / 200) << "first: " << first;
}

// The host method (Embree traces the camera rays, the resolve rebuilds the images from its hits)
// resolves exactly as the visibility method does: where both name the same triangle, every image
// is bit-identical; they may name different triangles only where a pixel's ray grazes an edge
// (the raster's fill rule and snapping against Embree's intersection test; on night_market's
// 147k triangles at 160x90 many pixels lie within rounding of an edge: 0.19% differ, the same
// bound as the forward method's against the visibility method's). With a sub-pixel jitter and a
// moving camera, so the host's camera rays follow the raster's jittered samples (a wrong jitter
// sign or scale moves every edge and fails the bound many times over).
TEST_F(GBufferTest, HostMethodMatchesVisibilityMethod) {
  const Level level = load_level_argument("night_market");
  const lighting::SceneData scene = lighting::build_scene_data(level);
  gpu::FrameConstants fc = moving_constants_for(level.camera);
  fc.jitter = glm::vec4(0.31f, -0.27f, -0.12f, 0.4f);
  test::GBufferHarness visibility(device, shaders, scene,
                                  {.method = lighting::GBufferMethod::Visibility});
  test::GBufferHarness host(device, shaders, scene, {.method = lighting::GBufferMethod::Host});
  const test::GBufferImages v = *visibility.render(fc, true);
  const test::GBufferImages h = *host.render(fc, true);
  EXPECT_EQ(count_non_finite(h), 0u);
  std::size_t different = 0, surfaces = 0, unequal = 0;
  for (std::size_t i = 0; i < v.ids.size(); ++i) {
    if (v.ids[i] != h.ids[i]) {
      ++different;
      continue;
    }
    surfaces += v.ids[i].x != gpu::kNoInstance ? 1 : 0;
    const bool same = v.position[i] == h.position[i] && v.normal[i] == h.normal[i] &&
                      v.albedo_roughness[i] == h.albedo_roughness[i] &&
                      v.emission_metallic[i] == h.emission_metallic[i] &&
                      v.motion[i] == h.motion[i];
    unequal += same ? 0 : 1;
  }
  RecordProperty("different_pixels", std::to_string(different));
  EXPECT_LE(different, v.ids.size() / 200) << "more than 0.5% of the pixels see another triangle";
  EXPECT_EQ(unequal, 0u) << "the same triangle resolved differently";
  EXPECT_GT(surfaces, v.ids.size() / 2) << "the camera should mostly see geometry";
}

// The host method on the emitter-scaling level at 10^5 panel triangles: the same triangles as the
// visibility method's cull and raster (the panels' triangles are far smaller than a pixel).
TEST_F(GBufferTest, HostMethodMatchesVisibilityMethodOnSubPixelTriangles) {
  nlohmann::json json;
  std::ifstream(std::filesystem::path(LANTERN_SOURCE_DIR) / "content/levels/light_panels.json") >>
      json;
  json.erase("budgets");  // relative to content/levels
  json["generators"][0]["emitter_triangles"] = 100000;
  const std::filesystem::path file =
      std::filesystem::temp_directory_path() /
      fmt::format("lantern_gbuffer_panels_{}.json", static_cast<long>(::getpid()));
  std::ofstream(file) << json.dump();
  const Level level = load_level(file);
  std::filesystem::remove(file);
  const lighting::SceneData scene = lighting::build_scene_data(level);
  const gpu::FrameConstants fc = constants_for(level.camera);
  test::GBufferHarness visibility(device, shaders, scene,
                                  {.method = lighting::GBufferMethod::Visibility});
  test::GBufferHarness host(device, shaders, scene, {.method = lighting::GBufferMethod::Host});
  const test::GBufferImages v = *visibility.render(fc, true);
  const test::GBufferImages h = *host.render(fc, true);
  std::size_t different = 0;
  for (std::size_t i = 0; i < v.ids.size(); ++i) different += v.ids[i] != h.ids[i] ? 1 : 0;
  EXPECT_LE(different, v.ids.size() / 1000);
}

INSTANTIATE_TEST_SUITE_P(Methods, GBufferMethodTest,
                         ::testing::Values(lighting::GBufferMethod::Visibility,
                                           lighting::GBufferMethod::Forward,
                                           lighting::GBufferMethod::Host),
                         [](const ::testing::TestParamInfo<lighting::GBufferMethod>& param) {
                           return std::string(lighting::gbuffer_method_name(param.param)) ==
                                          "forward"
                                      ? "Forward"
                                      : param.param == lighting::GBufferMethod::Host ? "Host"
                                                                                     : "Visibility";
                         });

// Auto: Forward for frames with at most one triangle per kForwardPixelsPerTriangle pixels.
TEST(GBufferMethodChoice, AutoPicksForwardOnlyForFewTrianglesPerPixel) {
  using lighting::GBufferMethod;
  using lighting::GBufferPass;
  EXPECT_EQ(GBufferPass::method_for(GBufferMethod::Auto, 122, 320, 180), GBufferMethod::Forward);
  EXPECT_EQ(GBufferPass::method_for(GBufferMethod::Auto, 147518, 320, 180),
            GBufferMethod::Visibility);
  EXPECT_EQ(GBufferPass::method_for(GBufferMethod::Auto, 147518, 1920, 1080),
            GBufferMethod::Visibility);
  EXPECT_EQ(GBufferPass::method_for(GBufferMethod::Auto, 320 * 180 / 16, 320, 180),
            GBufferMethod::Forward);
  EXPECT_EQ(GBufferPass::method_for(GBufferMethod::Auto, 320 * 180 / 16 + 1, 320, 180),
            GBufferMethod::Visibility);
  EXPECT_EQ(GBufferPass::method_for(GBufferMethod::Visibility, 1, 320, 180),
            GBufferMethod::Visibility);
  // With host visibility (a CPU device) the host method takes over from one triangle per pixel
  // (night_market at 320x180, not at 640x360), never from Forward.
  EXPECT_EQ(GBufferPass::method_for(GBufferMethod::Auto, 147518, 320, 180, true),
            GBufferMethod::Host);
  EXPECT_EQ(GBufferPass::method_for(GBufferMethod::Auto, 147518, 640, 360, true),
            GBufferMethod::Visibility);
  EXPECT_EQ(GBufferPass::method_for(GBufferMethod::Auto, 320 * 180, 320, 180, true),
            GBufferMethod::Host);
  EXPECT_EQ(GBufferPass::method_for(GBufferMethod::Auto, 320 * 180 - 1, 320, 180, true),
            GBufferMethod::Visibility);
  EXPECT_EQ(GBufferPass::method_for(GBufferMethod::Auto, 122, 320, 180, true),
            GBufferMethod::Forward);
  EXPECT_EQ(GBufferPass::method_for(GBufferMethod::Visibility, 147518, 320, 180, true),
            GBufferMethod::Visibility);
  EXPECT_EQ(GBufferPass::method_for(GBufferMethod::Forward, 1u << 30, 320, 180),
            GBufferMethod::Forward);
}

// Auto on a small scene runs Forward, and warm_up compiles both methods' pipelines without error.
TEST_F(GBufferTest, AutoMethodRendersCornellLights) {
  const Level level = load_level_argument("cornell_lights");
  const lighting::SceneData scene = lighting::build_scene_data(level);
  test::GBufferHarness harness(device, shaders, scene);
  harness.warm_up();
  const gpu::FrameConstants fc = constants_for(level.camera);
  const test::GBufferImages g = *harness.render(fc, true);
  EXPECT_EQ(count_non_finite(g), 0u);
  expect_agreement(compare_with_cpu(scene, fc, g), "auto");
  EXPECT_LT(harness.last_ms("gbuffer.cull"), 0.0) << "Auto should have picked Forward";
}

}  // namespace
}  // namespace lantern
