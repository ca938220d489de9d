// Numerical extremes (gpu): radiance from 1e-8 to 1e8, no light, one light, many emitters,
// zero-area and sliver emitters, the scene at 1e-3 / 1e4 scale and 1e5 away from the origin, the
// camera inside geometry, a camera cut every frame, M cap 1 and 10^4, and every half-precision
// storage path at its overflow edge — for baseline and restir (and the reference integrator where
// it is cheap). Each: no crash, no NaN/Inf pixel, zero validation errors (GpuTest), and where a
// reference is meaningful, the image mean within a stated tolerance of it (the reference
// integrator's image, a closed form, or the same scene at unit scale).
//
// Images are 64x36 (2304 pixels): means over all pixels of a few frames. Tolerances below say
// what noise and what precision they absorb; measured values are in the comments.
#include <gtest/gtest.h>

#include <cstdio>
#include <glm/gtc/matrix_transform.hpp>
#include <limits>

#include "engine/core/error.h"
#include "engine/level/level_loader.h"
#include "engine/level/primitives.h"
#include "lighting/scene/scene_data.h"
#include "runtime/gpu/shader_library.h"
#include "shared/bvh.h"
#include "tests/extremes/extremes_support.h"
#include "tests/runtime/gpu_test_support.h"

namespace lantern::extremes {
namespace {

using runtime::ImageRGBA32F;
using runtime::mean_rgb;

class ExtremesTest : public runtime::test::GpuTest {
 protected:
  runtime::ShaderLibrary shaders;

  ImageRGBA32F mean_of(const Level& level, const IntegratorConfig& config, std::uint32_t frames,
                       std::uint32_t seed = 1) {
    ImageRGBA32F image = render_mean(device, shaders, level, config, frames, 64, 36, seed);
    EXPECT_EQ(image.count_non_finite(), 0u) << name_of(config) << " on " << level.name;
    EXPECT_GE(min_channel(image), 0.0) << name_of(config) << " on " << level.name;
    return image;
  }
};

// Reference: 16 spp x 4 frames = 64 MIS samples per pixel; its image mean is within ~0.5% of the
// converged value on these scenes (measured: 4x more samples moves it < 0.3%).
ImageRGBA32F reference_mean(runtime::Device& device, runtime::ShaderLibrary& shaders,
                            const Level& level) {
  return render_mean(device, shaders, level, reference(16), 4, 64, 36, 7);
}

// ---------------------------------------------------------------------------------------------
// Radiance 1e-8 .. 1e8 in one scene: 17 small quads, one per decade, over the room. The mean is
// dominated by the brightest; the test is that nothing overflows, underflows into NaN or loses
// the image: baseline and restir means within 5% of the reference (8 frames each; measured
// noise of the 8-frame mean ~1-2%).
TEST_F(ExtremesTest, RadianceFrom1eMinus8To1e8InOneScene) {
  std::vector<Emitter> emitters;
  for (int d = -8; d <= 8; ++d) {
    const int i = d + 8;
    emitters.push_back({glm::vec3(-2.4f + 0.8f * static_cast<float>(i % 6),
                                  1.6f + 0.1f * static_cast<float>(i % 3),
                                  -1.8f + 1.2f * static_cast<float>(i / 6)),
                        std::pow(10.0f, static_cast<float>(d)), 0.25f});
  }
  const Level level = lit_room(emitters, "radiance_span");
  const ImageRGBA32F ref = reference_mean(device, shaders, level);
  ASSERT_EQ(ref.count_non_finite(), 0u);
  ASSERT_GT(mean_rgb(ref), 0.0);
  for (const IntegratorConfig& config : {baseline(), restir()}) {
    const ImageRGBA32F image = mean_of(level, config, 8);
    const double d = rel_diff(mean_rgb(image), mean_rgb(ref));
    std::printf("[extremes] radiance span %s: mean %.6g reference %.6g rel diff %.4f\n",
                name_of(config), mean_rgb(image), mean_rgb(ref), d);
    EXPECT_LT(d, 0.05) << name_of(config);
  }
}

// Radiance scale invariance: the same scene with every emitter x1e-8 and x1e8 renders the unit
// image times the factor. Same seed, so the same random numbers: sampling (power alias table,
// RIS weights, MIS) is invariant to a common factor, and the only differences are float rounding
// (the factor is not a power of two) and the packed reservoir's half-precision p̂ (saturating at
// 65504; re-evaluated wherever it matters, so it should not show). Tolerance: mean within 1e-3
// and relative MSE < 1e-4 of the unit image.
TEST_F(ExtremesTest, RadianceScaleInvarianceFrom1eMinus8To1e8) {
  const Level unit = lit_room(two_lights(), "scale_unit");
  for (const IntegratorConfig& config : {baseline(), restir()}) {
    const ImageRGBA32F base = mean_of(unit, config, 4);
    ASSERT_GT(mean_rgb(base), 0.0);
    for (const float k : {1e-8f, 1e8f}) {
      Level scaled = unit;
      scale_radiance(scaled, k);
      ImageRGBA32F image = mean_of(scaled, config, 4);
      for (float& v : image.pixels) v /= k;
      for (std::size_t i = 3; i < image.pixels.size(); i += 4) image.pixels[i] = 1.0f;
      const double d = rel_diff(mean_rgb(image), mean_rgb(base));
      const double rmse = runtime::relative_mse(image, base);
      std::printf("[extremes] radiance x%g %s: mean ratio %.7f relMSE %.3g\n", k, name_of(config),
                  mean_rgb(image) / mean_rgb(base), rmse);
      EXPECT_LT(d, 1e-3) << name_of(config) << " x" << k;
      EXPECT_LT(rmse, 1e-4) << name_of(config) << " x" << k;
    }
  }
}

// ---------------------------------------------------------------------------------------------
// No light at all: every integrator renders exact black (no sky, no emitter, no environment) —
// in particular restir must not divide by an empty alias table or a zero M sum.
TEST_F(ExtremesTest, ZeroLightsRenderBlackAndFinite) {
  const Level level = room("no_lights");
  for (const IntegratorConfig& config :
       {baseline(), restir(), restir({{"bsdf_candidates", "2"}, {"spatial_passes", "2"}}),
        restir({{"bias_correction", "balance"}}), reference(4)}) {
    const std::vector<ImageRGBA32F> frames =
        render_static(device, shaders, level, config, 3, false);
    for (const ImageRGBA32F& image : frames) {
      EXPECT_EQ(image.count_non_finite(), 0u) << name_of(config);
      EXPECT_EQ(max_channel(image), 0.0) << name_of(config);
      EXPECT_EQ(min_channel(image), 0.0) << name_of(config);
    }
  }
}

// One light: with a single emitter light selection is trivial, so any normalisation error shows.
// Baseline and restir means within 3% of the reference (measured noise of 8-frame means < 1%).
TEST_F(ExtremesTest, OneLightMatchesReference) {
  const Level level = lit_room({{glm::vec3(0.2f, 2.0f, 0.3f), 15.0f, 0.7f}}, "one_light");
  const ImageRGBA32F ref = reference_mean(device, shaders, level);
  ASSERT_GT(mean_rgb(ref), 0.0);
  for (const IntegratorConfig& config : {baseline(), restir()}) {
    const ImageRGBA32F image = mean_of(level, config, 8);
    const double d = rel_diff(mean_rgb(image), mean_rgb(ref));
    std::printf("[extremes] one light %s: mean %.6g reference %.6g rel diff %.4f\n",
                name_of(config), mean_rgb(image), mean_rgb(ref), d);
    EXPECT_LT(d, 0.03) << name_of(config);
  }
}

// One point light over a Lambertian floor seen straight down: the centre pixel is the closed form
// rho/pi * I / h^2, within 1% (one light, exact sampling, no visibility noise).
TEST_F(ExtremesTest, OnePointLightMatchesClosedForm) {
  Level level;
  level.name = "one_point_light";
  add_mesh(level, make_plane(glm::vec2(20.0f, 20.0f)));
  add_material(level, make_lambert(0.5f));
  level.instances.push_back(place("floor", 0, 0, glm::mat4(1.0f)));
  Light light;
  light.type = LightType::Point;
  light.color = glm::vec3(3.0f, 2.0f, 1.0f);
  light.position = glm::vec3(0.0f, 1.5f, 0.0f);
  level.lights.push_back(light);
  level.camera.position = glm::vec3(0.0f, 4.0f, 0.0f);
  level.camera.orientation = look_at_orientation(level.camera.position, glm::vec3(0.0f));
  level.camera.yfov = 0.6f;
  level.has_camera = true;
  for (const IntegratorConfig& config : {baseline(), restir()}) {
    const ImageRGBA32F image = render_mean(device, shaders, level, config, 2, 41, 31);
    EXPECT_EQ(image.count_non_finite(), 0u);
    const float* centre = image.at(20, 15);
    for (int c = 0; c < 3; ++c) {
      const float expected = 0.5f / 3.14159265f * light.color[c] / (1.5f * 1.5f);
      EXPECT_NEAR(centre[c], expected, 0.01f * expected) << name_of(config) << " channel " << c;
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Zero-area emissive triangles: the loader's mesh validation (LevelBuilder::add_mesh, what the
// JSON and glTF loaders call) drops them and counts them for its warning.
TEST_F(ExtremesTest, LoaderDropsZeroAreaTriangles) {
  Level level;
  LoadDiagnostics diagnostics;
  LevelBuilder builder(level, diagnostics);
  Mesh mesh = make_plane(glm::vec2(1.0f, 1.0f));
  const auto v = static_cast<std::uint32_t>(mesh.positions.size());
  mesh.positions.push_back(glm::vec3(0.0f));
  mesh.positions.push_back(glm::vec3(1.0f, 0.0f, 0.0f));
  mesh.positions.push_back(glm::vec3(2.0f, 0.0f, 0.0f));  // collinear
  for (int i = 0; i < 3; ++i) mesh.normals.push_back(glm::vec3(0.0f, 1.0f, 0.0f));
  mesh.uvs.resize(mesh.positions.size());
  mesh.indices.insert(mesh.indices.end(), {v, v + 1, v + 2});  // zero area, collinear
  mesh.indices.insert(mesh.indices.end(), {v, v, v + 1});      // repeated vertex
  builder.add_mesh(mesh, "extremes");
  EXPECT_EQ(diagnostics.degenerate_triangles, 2u);
  EXPECT_EQ(level.meshes.at(0).triangle_count(), 2u);
}

// An emitter mesh: a quad plus triangles that no loader lets through (built directly as Level
// data): coincident vertices, collinear vertices, a 1 m x 1e-7 m sliver, a 1e-20 m^2 speck and a
// needle whose area is 1e-9 of its edge squared.
Mesh degenerate_emitter_mesh(bool with_degenerates) {
  Mesh mesh = make_plane(glm::vec2(0.6f, 0.6f));
  if (!with_degenerates) return mesh;
  const auto add_triangle = [&mesh](glm::vec3 a, glm::vec3 b, glm::vec3 c) {
    const auto v = static_cast<std::uint32_t>(mesh.positions.size());
    for (const glm::vec3& p : {a, b, c}) {
      mesh.positions.push_back(p);
      mesh.normals.push_back(glm::vec3(0.0f, 1.0f, 0.0f));
      mesh.uvs.push_back(glm::vec2(0.0f));
    }
    // Counter-clockwise seen from +Y (the plane's front): a, c, b.
    mesh.indices.insert(mesh.indices.end(), {v, v + 2, v + 1});
  };
  add_triangle(glm::vec3(0.1f, 0.0f, 0.1f), glm::vec3(0.1f, 0.0f, 0.1f), glm::vec3(0.1f, 0.0f, 0.1f));
  add_triangle(glm::vec3(-0.3f, 0.0f, 0.0f), glm::vec3(0.0f, 0.0f, 0.0f), glm::vec3(0.3f, 0.0f, 0.0f));
  add_triangle(glm::vec3(-0.5f, 0.0f, 0.2f), glm::vec3(0.5f, 0.0f, 0.2f),
               glm::vec3(0.0f, 0.0f, 0.2f + 1e-7f));
  add_triangle(glm::vec3(0.2f, 0.0f, -0.2f), glm::vec3(0.2f + 1e-10f, 0.0f, -0.2f),
               glm::vec3(0.2f, 0.0f, -0.2f + 1e-10f));
  add_triangle(glm::vec3(-0.4f, 0.0f, -0.1f), glm::vec3(0.4f, 0.0f, -0.1f),
               glm::vec3(0.0f, 0.0f, -0.1f + 1.6e-9f));
  return mesh;
}

Level emitter_mesh_room(Mesh emitter, float radiance, const std::string& name) {
  Level level = room(name);
  const std::uint32_t mesh = add_mesh(level, std::move(emitter));
  const std::uint32_t mat = add_material(level, emissive(radiance));
  level.instances.push_back(
      place("emitter", mesh, mat,
            glm::translate(glm::mat4(1.0f), glm::vec3(0.2f, 2.0f, 0.3f)) *
                glm::mat4_cast(glm::angleAxis(glm::pi<float>(), glm::vec3(1.0f, 0.0f, 0.0f)))));
  return level;
}

// The degenerate triangles become lights of (nearly) zero power: they must not produce NaN (1/area
// point densities), and the image equals the clean quad's: same seed, means within 1% (their
// combined flux is < 1e-6 of the quad's; the 1% absorbs different random-number use when the
// alias table has more entries).
TEST_F(ExtremesTest, ZeroAreaAndSliverEmittersPushedThroughLevelData) {
  const Level dirty = emitter_mesh_room(degenerate_emitter_mesh(true), 15.0f, "dirty_emitter");
  const Level clean = emitter_mesh_room(degenerate_emitter_mesh(false), 15.0f, "clean_emitter");
  const lighting::SceneData scene = lighting::build_scene_data(dirty);
  ASSERT_EQ(scene.emissive_triangles, 7u) << "all seven triangles reach the light table";
  for (const IntegratorConfig& config :
       {baseline(), restir(), restir({{"bsdf_candidates", "2"}}), reference(8)}) {
    const ImageRGBA32F a = mean_of(dirty, config, 4);
    const ImageRGBA32F b = mean_of(clean, config, 4);
    const double d = rel_diff(mean_rgb(a), mean_rgb(b));
    std::printf("[extremes] degenerate emitters %s: mean %.6g clean %.6g rel diff %.4f\n",
                name_of(config), mean_rgb(a), mean_rgb(b), d);
    EXPECT_LT(d, 0.01) << name_of(config);
  }
}

// An emitter made only of slivers (1 m x 1e-4 m needles, radiance 3e4 so their flux matters):
// selection by power and 1/area point densities of ~2e4 per m^2. Baseline and restir means
// within 5% of the reference (8 frames; slivers are hard to hit by BSDF sampling, so the
// reference's MIS leans on light sampling: its noise is larger, ~2%).
TEST_F(ExtremesTest, SliverOnlyEmitterMatchesReference) {
  Mesh mesh;
  for (int i = 0; i < 16; ++i) {
    const float z = -0.4f + 0.05f * static_cast<float>(i);
    const auto v = static_cast<std::uint32_t>(mesh.positions.size());
    for (const glm::vec3& p : {glm::vec3(-0.5f, 0.0f, z), glm::vec3(0.5f, 0.0f, z),
                               glm::vec3(0.0f, 0.0f, z + 1e-4f)}) {
      mesh.positions.push_back(p);
      mesh.normals.push_back(glm::vec3(0.0f, 1.0f, 0.0f));
    }
    mesh.indices.insert(mesh.indices.end(), {v, v + 2, v + 1});
  }
  const Level level = emitter_mesh_room(std::move(mesh), 3e4f, "sliver_emitter");
  const ImageRGBA32F ref = reference_mean(device, shaders, level);
  ASSERT_GT(mean_rgb(ref), 0.0);
  for (const IntegratorConfig& config : {baseline(), restir()}) {
    const ImageRGBA32F image = mean_of(level, config, 8);
    const double d = rel_diff(mean_rgb(image), mean_rgb(ref));
    std::printf("[extremes] sliver emitter %s: mean %.6g reference %.6g rel diff %.4f\n",
                name_of(config), mean_rgb(image), mean_rgb(ref), d);
    EXPECT_LT(d, 0.05) << name_of(config);
  }
}

// ---------------------------------------------------------------------------------------------
// Scale and translation. Direct lighting from area lights is scale-invariant (L_o = f * integral
// of L cos cos / d^2 dA: d^2 and dA scale alike) when the camera (and its near plane) scales too,
// so each transformed scene must render the unit scene's image. Same seed: the images differ
// only by float precision and by epsilons with an absolute part. Tolerance on the image mean:
//   x1e-3, x1e4: 2%   (positions keep 24 bits of relative precision at any scale; the shadow
//                      epsilon is absolute 1e-4 m below |p| = 1, i.e. 1/60 of the 6 mm room at
//                      x1e-3. Measured: identical means, relMSE 3e-12 (x1e-3) and 3e-14 (x1e4))
//   +1e5 m:       5%   (float ulp at 1e5 is 2^-7 = 7.8 mm: the geometry snaps to an 8 mm grid,
//                      ~770 steps across the 6 m room, and G-buffer positions carry that error.
//                      The relative shadow epsilon (bvh_position_epsilon, 4e-6 |p| = 0.4 m at
//                      1e5) loses contact shadows within 0.4 m of an occluder. Before the fix the
//                      epsilon was 1e-4 |p| = 10 m and erased every shadow (mean +3.6%, relMSE
//                      0.027); SceneTranslatedTo1e5KeepsShadows below pins the fix.)
struct ScaleCase {
  const char* name;
  float scale;
  glm::vec3 translation;
  double tolerance;
};

TEST_F(ExtremesTest, SceneScaledAndTranslatedMatchesUnitScene) {
  const Level unit = lit_room(two_lights(), "unit_room");
  const ScaleCase cases[] = {
      {"x1e-3", 1e-3f, glm::vec3(0.0f), 0.02},
      {"x1e4", 1e4f, glm::vec3(0.0f), 0.02},
      {"+1e5", 1.0f, glm::vec3(1e5f, 1e5f, 1e5f), 0.05},
  };
  for (const IntegratorConfig& config : {baseline(), restir()}) {
    const ImageRGBA32F base = mean_of(unit, config, 4);
    ASSERT_GT(mean_rgb(base), 0.0);
    for (const ScaleCase& c : cases) {
      Level level = unit;
      transform_level(level, c.scale, c.translation);
      const ImageRGBA32F image = mean_of(level, config, 4);
      const double d = rel_diff(mean_rgb(image), mean_rgb(base));
      std::printf("[extremes] scene %s %s: mean %.6g unit %.6g rel diff %.4f relMSE %.3g\n", c.name,
                  name_of(config), mean_rgb(image), mean_rgb(base), d,
                  runtime::relative_mse(image, base));
      EXPECT_LT(d, c.tolerance) << name_of(config) << " " << c.name;
    }
  }
}

// The shadow-ray epsilon (shaders/shared/bvh.h, shared by every visibility backend) at the
// coordinates of the scene translated to 1e5: a light 2 m above a floor point is traced (the
// epsilon is relative to float precision), so occluders there cast shadows. It used to report
// such a pair visible without tracing (-1).
TEST(ExtremesShadowEpsilon, ShadowEpsilonAt1e5) {
  const glm::vec3 floor_point(1e5f, 1e5f, 1e5f);
  const glm::vec3 light = floor_point + glm::vec3(0.3f, 2.0f, 0.5f);
  // Fixed: the epsilon is relative (~32 ulps), 0.4 m at 1e5, so a 2.1 m segment is traced.
  EXPECT_GT(gpu::bvh_shadow_t_epsilon(floor_point, light), 0.0f);
  // Near the origin the same pair is traced (epsilon 1e-4 m of a 2.1 m segment).
  EXPECT_GT(gpu::bvh_shadow_t_epsilon(glm::vec3(0.0f), glm::vec3(0.3f, 2.0f, 0.5f)), 0.0f);
}

// The +1e5 room must keep its shadows: relative MSE against the unit room < 1e-2 (it was 0.027
// while the shadow epsilon grew as 1e-4 |p| = 10 m and erased every shadow). What remains is
// precision: positions on an 8 mm grid, and the relative epsilon (4e-6 |p| = 0.4 m) loses contact
// shadows within 0.4 m of an occluder. Measured 0.0029 (baseline) and 0.0030 (restir).
TEST_F(ExtremesTest, SceneTranslatedTo1e5KeepsShadows) {
  const Level unit = lit_room(two_lights(), "unit_room");
  Level far = unit;
  transform_level(far, 1.0f, glm::vec3(1e5f));
  for (const IntegratorConfig& config : {baseline(), restir()}) {
    const ImageRGBA32F base = mean_of(unit, config, 4);
    const ImageRGBA32F image = mean_of(far, config, 4);
    EXPECT_LT(runtime::relative_mse(image, base), 1e-2) << name_of(config);
  }
}

// ---------------------------------------------------------------------------------------------
// Camera inside geometry. (a) Inside the closed occluder box, lights outside: the camera sees the
// box's back faces, every shading point is shut in, the image is black; allowed: mean < 1e-3 of
// the room seen from outside (leaks through the shadow epsilon at the box's edges). (b) The near
// plane cutting through the floor (camera 1 cm above it, znear 5 cm, looking along it): finite,
// mean within 5% of the reference. (c) The camera exactly in the floor plane (the floor seen
// edge-on): mean within 5% of the reference.
TEST_F(ExtremesTest, CameraInsideGeometry) {
  const Level outside = lit_room(two_lights(), "outside");
  Level inside = outside;
  inside.name = "inside_box";
  inside.camera.position = glm::vec3(-0.9f, 0.4f, 0.0f);  // the occluder's centre
  inside.camera.orientation =
      look_at_orientation(inside.camera.position, glm::vec3(-0.9f, 0.4f, -1.0f));
  const double room_mean = mean_rgb(mean_of(outside, baseline(), 2));
  for (const IntegratorConfig& config : {baseline(), restir(), reference(4)}) {
    const double m = mean_rgb(mean_of(inside, config, 2));
    std::printf("[extremes] camera inside box %s: mean %.6g (room %.6g)\n", name_of(config), m,
                room_mean);
    EXPECT_LT(m, 1e-3 * room_mean) << name_of(config);
  }

  Level grazing = outside;
  grazing.name = "grazing";
  grazing.camera.position = glm::vec3(0.0f, 0.01f, 2.5f);
  grazing.camera.orientation =
      look_at_orientation(grazing.camera.position, glm::vec3(0.0f, -0.3f, 0.0f));
  const ImageRGBA32F ref = reference_mean(device, shaders, grazing);
  for (const IntegratorConfig& config : {baseline(), restir()}) {
    const ImageRGBA32F image = mean_of(grazing, config, 8);
    const double d = rel_diff(mean_rgb(image), mean_rgb(ref));
    std::printf("[extremes] near plane through floor %s: mean %.6g reference %.6g rel diff %.4f\n",
                name_of(config), mean_rgb(image), mean_rgb(ref), d);
    EXPECT_LT(d, 0.05) << name_of(config);
  }

  Level in_plane = outside;
  in_plane.name = "in_plane";
  in_plane.camera.position = glm::vec3(0.0f, 0.0f, 2.5f);
  in_plane.camera.orientation =
      look_at_orientation(in_plane.camera.position, glm::vec3(0.0f, 0.0f, 0.0f));
  const ImageRGBA32F in_plane_ref = reference_mean(device, shaders, in_plane);
  ASSERT_GT(mean_rgb(in_plane_ref), 0.0);
  for (const IntegratorConfig& config : {baseline(), restir()}) {
    const ImageRGBA32F image = mean_of(in_plane, config, 8);
    const double d = rel_diff(mean_rgb(image), mean_rgb(in_plane_ref));
    std::printf("[extremes] camera in the floor plane %s: mean %.6g reference %.6g rel diff %.4f\n",
                name_of(config), mean_rgb(image), mean_rgb(in_plane_ref), d);
    EXPECT_LT(d, 0.05) << name_of(config);
  }
}

// ---------------------------------------------------------------------------------------------
// A camera cut every frame (World::request_camera_cut before each step): restir runs without
// history every frame. On a static level the mean over 8 frames is an unbiased estimate, within
// 5% of the reference (per-frame restir without history is noisier: measured ~2%).
TEST_F(ExtremesTest, CameraCutEveryFrame) {
  const auto level = std::make_shared<const Level>(lit_room(two_lights(), "cut_every_frame"));
  const ImageRGBA32F ref = reference_mean(device, shaders, *level);
  for (const IntegratorConfig& config : {baseline(), restir()}) {
    lighting::HeadlessSession session(device, shaders, level,
                                      {.integrator = config, .width = 64, .height = 36});
    session.warm_up();
    runtime::ImageAccumulator accumulator;
    for (int f = 0; f < 8; ++f) {
      session.world().request_camera_cut();
      const FrameSnapshot& snapshot = session.step_world();
      EXPECT_TRUE(snapshot.camera_cut);
      ImageRGBA32F image;
      session.render(snapshot, &image);
      EXPECT_EQ(image.count_non_finite(), 0u) << name_of(config) << " frame " << f;
      accumulator.add(image);
    }
    const double d = rel_diff(mean_rgb(accumulator.mean()), mean_rgb(ref));
    std::printf("[extremes] cut every frame %s: mean %.6g reference %.6g rel diff %.4f\n",
                name_of(config), mean_rgb(accumulator.mean()), mean_rgb(ref), d);
    EXPECT_LT(d, 0.05) << name_of(config);
  }
}

// The same along a moving camera path with moving objects (cornell_lights' dolly), every frame:
// no pixel reuses history (restir.temporal's status, read through the disocclusion debug view:
// every surface pixel kRestirStatusNoHistory on each of the 10 frames), and the frames' radiance
// is an unbiased estimate of their snapshots: 4 runs with distinct seeds, the sum over their 40
// frames of the lit pixels within 5% of a 16-frame baseline mean of each snapshot. Lit pixels:
// an independent baseline estimate (another seed) below 5, so the emitters (identical in both)
// are left out; choosing them from the reference itself biased the comparison by +15% (a
// baseline run against that mask read +15%). Noise: one frame's lit sum has sd ~8% here (44
// emitters spanning 10^4), so the 40-frame sum ~1.3%, the reference ~0.6%: 5% is ~3.5 sd.
TEST_F(ExtremesTest, CameraCutEveryFrameAlongAPath) {
  Level cornell = load_level_argument("cornell_lights");
  cornell.camera_path = "dolly";
  const auto level = std::make_shared<const Level>(std::move(cornell));
  constexpr int kFrames = 10;
  constexpr int kRuns = 4;
  std::vector<FrameSnapshot> snapshots;
  {
    lighting::HeadlessSession status_session(
        device, shaders, level,
        {.integrator = restir({{"debug_view", "disocclusion"}}), .width = 64, .height = 36});
    status_session.warm_up();
    for (int f = 0; f < kFrames; ++f) {
      status_session.world().request_camera_cut();
      snapshots.push_back(status_session.step_world());
      ImageRGBA32F debug;
      status_session.render(snapshots.back(), &debug);
      std::size_t surface = 0, reused = 0;
      for (std::size_t p = 0; p < debug.pixels.size() / 4; ++p) {
        const float r = debug.pixels[4 * p], g = debug.pixels[4 * p + 1];
        if (r == 0.0f && g == 0.0f) continue;  // sky
        ++surface;
        reused += r == 1.0f && g == 0.0f ? 0 : 1;
      }
      EXPECT_TRUE(snapshots.back().camera_cut);
      EXPECT_GT(surface, 1000u) << "frame " << f;
      EXPECT_EQ(reused, 0u) << "frame " << f << ": pixels reusing history after a cut";
    }
  }
  // Per frame: the lit mask and the reference.
  std::vector<std::vector<std::uint8_t>> lit(kFrames);
  std::vector<double> reference(kFrames, 0.0);
  for (const std::uint32_t seed : {99u, 1u}) {
    lighting::HeadlessSession base(device, shaders, level,
                                   {.integrator = baseline(), .width = 64, .height = 36, .seed = seed});
    base.warm_up();
    for (int f = 0; f < kFrames; ++f) {
      runtime::ImageAccumulator acc;
      for (int k = 0; k < 16; ++k) {
        ImageRGBA32F r;
        base.render(snapshots[f], &r);
        acc.add(r);
      }
      const ImageRGBA32F mean = acc.mean();
      if (seed == 99u) {
        lit[f].resize(mean.pixels.size());
        for (std::size_t i = 0; i < mean.pixels.size(); ++i)
          lit[f][i] = i % 4 != 3 && mean.pixels[i] < 5.0f ? 1 : 0;
      } else {
        for (std::size_t i = 0; i < mean.pixels.size(); ++i)
          if (lit[f][i]) reference[f] += mean.pixels[i];
      }
    }
  }
  double sum = 0.0, reference_sum = 0.0;
  for (int run = 0; run < kRuns; ++run) {
    lighting::HeadlessSession session(
        device, shaders, level,
        {.integrator = restir(), .width = 64, .height = 36, .seed = 5u + std::uint32_t(run)});
    session.warm_up();
    for (int f = 0; f < kFrames; ++f) {
      session.world().request_camera_cut();
      const FrameSnapshot& snapshot = session.step_world();
      ImageRGBA32F image;
      session.render(snapshot, &image);
      EXPECT_EQ(image.count_non_finite(), 0u) << "run " << run << " frame " << f;
      for (std::size_t i = 0; i < image.pixels.size(); ++i)
        if (lit[f][i]) sum += image.pixels[i];
      reference_sum += reference[f];
    }
  }
  const double d = sum / reference_sum - 1.0;
  std::printf("[extremes] cut every frame along the dolly: %d runs x %d frames, lit pixels "
              "relative to baseline %+.4f\n",
              kRuns, kFrames, d);
  EXPECT_LT(std::abs(d), 0.05);
}

// ---------------------------------------------------------------------------------------------
// M cap 1 (one light candidate, m_cap factor 1: history never outweighs the current frame) and
// 10^4 (ten candidates x factor 1000). Static scene, 12 frames: means within 4% of the reference
// (pairwise MIS is unbiased at any cap; with cap 10^4 the frames are strongly correlated, so the
// 12-frame mean carries the noise of few independent samples: measured ~1-2%).
TEST_F(ExtremesTest, MCapOneAndTenThousand) {
  const Level level = lit_room(two_lights(), "m_cap");
  const ImageRGBA32F ref = reference_mean(device, shaders, level);
  const std::pair<const char*, Settings> cases[] = {
      {"M cap 1", {{"light_candidates", "1"}, {"m_cap", "1"}}},
      {"M cap 1e4", {{"light_candidates", "10"}, {"m_cap", "1000"}}},
  };
  for (const auto& [what, settings] : cases) {
    const ImageRGBA32F image = mean_of(level, restir(settings), 12);
    const double d = rel_diff(mean_rgb(image), mean_rgb(ref));
    std::printf("[extremes] %s: mean %.6g reference %.6g rel diff %.4f\n", what, mean_rgb(image),
                mean_rgb(ref), d);
    EXPECT_LT(d, 0.04) << what;
  }
}

// ---------------------------------------------------------------------------------------------
// Half-precision storage at its overflow edge (65504 = the largest half; 65520 and up round to
// Inf). The paths, found by grepping shaders/ for packHalf2x16 / rgba16f / R16G16B16A16_SFLOAT:
//   1. gbuffer.albedo_roughness (rgba16f): base colour and roughness. The loader accepts any
//      base_color >= 0; Level data can carry anything.
//   2. PackedReservoir.m_target high half: p̂ as half (pack_target_pdf_half saturates at 65504).
//   3. PackedReservoir.m_target low 16 bits: M as an integer, saturating at 65535 (not a half, but
//      the same kind of edge: an M cap of 128 x 1000 = 128000 candidates).
//   (play's UI layer is rgba16f too but holds only UI colours in [0, 1]; not on a lighting path.)
// Each: baseline and restir finite and non-negative, and equal to a closed form of an image at
// an ordinary value (same seed, so the same random numbers):
//   - restir packs albedo and roughness into its surface record clamped to [0, 1]
//     (restir_surface_pack), and the BRDF clamps roughness: a restir image at any base colour or
//     roughness >= 1 is the image at 1.
//   - baseline reads GpuMaterial.base_color unclamped and its estimate is affine in the base
//     colour (light sampling does not depend on it; brdf_eval is affine in albedo): the image at
//     base colour v is b0 + v (b1 - b0) per pixel, b0 and b1 the images at 0 and 1, within 1e-3
//     relative (float rounding of the products); a pixel whose estimate overflows float in the
//     shading product is written black (the non-finite guard), allowed where the prediction
//     exceeds 1e30. The roughness is clamped by the BRDF: the image at roughness >= 1 is the
//     image at 1.
// Albedo: the two integrators disagree for any base colour > 1, which the JSON loader accepts
// (it checks >= 0 only): measured baseline mean 171 at 65504, 1.7e34 at 3e38. Reported, not fixed
// here (lighting/scene).
//
// Per pixel: |image - expected| <= tolerance x |expected| (+ 1e-6 x the expected image's mean),
// or the image black where the prediction exceeds `overflow` (0: never allowed).
::testing::AssertionResult matches_per_pixel(const ImageRGBA32F& image, const ImageRGBA32F& expected,
                                             double tolerance, double overflow = 0.0) {
  const double floor = 1e-6 * mean_rgb(expected);
  std::size_t bad = 0, black = 0, first = 0;
  for (std::size_t i = 0; i < image.pixels.size(); ++i) {
    if (i % 4 == 3) continue;
    const double v = image.pixels[i], e = expected.pixels[i];
    if (overflow > 0.0 && v == 0.0 && e > overflow) {
      ++black;
      continue;
    }
    if (std::abs(v - e) > tolerance * std::abs(e) + floor && bad++ == 0) first = i;
  }
  if (bad == 0) return ::testing::AssertionSuccess() << black << " overflowed to black";
  return ::testing::AssertionFailure()
         << bad << " channels differ; first: channel " << first << " is " << image.pixels[first]
         << ", expected " << expected.pixels[first];
}

// b0 + v (b1 - b0) per channel, in double (may exceed float: then +Inf, which only the overflow
// allowance accepts).
ImageRGBA32F affine_prediction(const ImageRGBA32F& b0, const ImageRGBA32F& b1, double v) {
  ImageRGBA32F out = b0;
  for (std::size_t i = 0; i < out.pixels.size(); ++i) {
    if (i % 4 == 3) continue;
    out.pixels[i] = static_cast<float>(double(b0.pixels[i]) +
                                       v * (double(b1.pixels[i]) - double(b0.pixels[i])));
  }
  return out;
}

TEST_F(ExtremesTest, HalfPrecisionAlbedoAtOverflowEdge) {
  auto with_albedo = [](float value) {
    Level level = lit_room(two_lights(), "albedo_edge");
    level.materials[2].base_color = glm::vec4(value, value, value, 1.0f);  // the glossy box
    return level;
  };
  const ImageRGBA32F restir_at_1 = mean_of(with_albedo(1.0f), restir(), 1);
  const ImageRGBA32F baseline_at_0 = mean_of(with_albedo(0.0f), baseline(), 1);
  const ImageRGBA32F baseline_at_1 = mean_of(with_albedo(1.0f), baseline(), 1);
  for (const float value : {65504.0f, 65520.0f, 1e5f, 3e38f}) {
    const Level level = with_albedo(value);
    const ImageRGBA32F r = mean_of(level, restir(), 1);
    const ImageRGBA32F b = mean_of(level, baseline(), 1);
    std::printf("[extremes] albedo %g: restir mean %.6g (at 1: %.6g), baseline mean %.6g max %.6g\n",
                value, mean_rgb(r), mean_rgb(restir_at_1), mean_rgb(b), max_channel(b));
    EXPECT_TRUE(matches_per_pixel(r, restir_at_1, 1e-6)) << "restir, albedo " << value;
    EXPECT_TRUE(matches_per_pixel(b, affine_prediction(baseline_at_0, baseline_at_1, value), 1e-3,
                                  1e30))
        << "baseline, albedo " << value;
  }
}

// A base colour the JSON loader accepts (1e30) under a 1e8 emitter: albedo x radiance overflows
// float in the shading product. No pixel may be Inf (house rule: shaders never write NaN/Inf), and
// the closed forms above hold: restir renders the floor (and back wall: the same material) at
// albedo 1; baseline is the affine prediction wherever it does not overflow, black where it does.
TEST_F(ExtremesTest, HugeAlbedoUnderHugeRadianceStaysFinite) {
  auto with_floor_albedo = [](float value) {
    Level level = lit_room(two_lights(1e8f), "albedo_overflow");
    level.materials[0].base_color = glm::vec4(value, value, value, 1.0f);  // floor, back wall
    return level;
  };
  const Level level = with_floor_albedo(1e30f);
  const ImageRGBA32F r = mean_of(level, restir(), 1);
  const ImageRGBA32F b = mean_of(level, baseline(), 1);
  std::printf("[extremes] albedo 1e30 x radiance 2e9: restir mean %.6g, baseline mean %.6g max "
              "%.6g\n",
              mean_rgb(r), mean_rgb(b), max_channel(b));
  EXPECT_TRUE(matches_per_pixel(r, mean_of(with_floor_albedo(1.0f), restir(), 1), 1e-6));
  const ImageRGBA32F prediction =
      affine_prediction(mean_of(with_floor_albedo(0.0f), baseline(), 1),
                        mean_of(with_floor_albedo(1.0f), baseline(), 1), 1e30);
  EXPECT_TRUE(matches_per_pixel(b, prediction, 1e-3, 1e30));
}

TEST_F(ExtremesTest, HalfPrecisionRoughnessAtOverflowEdge) {
  auto with_roughness = [](float value) {
    Level level = lit_room(two_lights(), "roughness_edge");
    level.materials[2].roughness = value;
    level.materials[2].metallic = 1.0f;
    return level;
  };
  for (const IntegratorConfig& config : {baseline(), restir({{"bsdf_candidates", "1"}})}) {
    const ImageRGBA32F at_1 = mean_of(with_roughness(1.0f), config, 2);
    for (const float value : {65504.0f, 65520.0f, 1e5f}) {
      const ImageRGBA32F image = mean_of(with_roughness(value), config, 2);
      std::printf("[extremes] roughness %g %s: mean %.6g (at 1: %.6g) max %.6g\n", value,
                  name_of(config), mean_rgb(image), mean_rgb(at_1), max_channel(image));
      EXPECT_TRUE(matches_per_pixel(image, at_1, 1e-6)) << name_of(config) << " roughness " << value;
    }
  }
}

// p̂ far above 65504 (radiance 1e6 and 1e8 seen from 1 m) with the boiling filter, the one place
// that reads the stored half p̂ (W * p̂ per tile): finite; the image scaled back by the radiance
// factor within 5% of the unit-radiance image with the same settings (the filter's decision is
// scale-invariant only if p̂ is stored exactly; saturation makes W * p̂ small for every pixel
// alike, which the relative tile test tolerates).
TEST_F(ExtremesTest, HalfPrecisionTargetPdfSaturation) {
  const Settings settings = {{"boiling_filter", "0.5"}, {"bsdf_candidates", "1"}};
  const Level unit = lit_room(two_lights(), "p_hat_edge");
  const ImageRGBA32F base = mean_of(unit, restir(settings), 4);
  for (const float k : {1e4f, 1e6f, 1e8f}) {
    Level level = unit;
    scale_radiance(level, k);
    const ImageRGBA32F image = mean_of(level, restir(settings), 4);
    const double ratio = mean_rgb(image) / k / mean_rgb(base);
    std::printf("[extremes] p-hat x%g (boiling filter 0.5): mean ratio %.5f\n", k, ratio);
    EXPECT_NEAR(ratio, 1.0, 0.05) << "x" << k;
  }
}

TEST_F(ExtremesTest, PackedMAtSaturation) {
  const Level level = lit_room(two_lights(), "m_edge");
  const ImageRGBA32F ref = reference_mean(device, shaders, level);
  for (const char* candidates : {"64", "128"}) {
    // 64 x 1000 = 64000 (just under 65535), 128 x 1000 = 128000 (stored M saturates).
    const ImageRGBA32F image =
        mean_of(level, restir({{"light_candidates", candidates}, {"m_cap", "1000"}}), 4);
    const double d = rel_diff(mean_rgb(image), mean_rgb(ref));
    std::printf("[extremes] M cap %s x 1000: mean %.6g reference %.6g rel diff %.4f\n", candidates,
                mean_rgb(image), mean_rgb(ref), d);
    EXPECT_LT(d, 0.04) << candidates;  // as MCapOneAndTenThousand
  }
}

}  // namespace
}  // namespace lantern::extremes
