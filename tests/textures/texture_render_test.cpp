// Textured materials end to end on lavapipe, against closed forms and quadratures computed here
// (the sRGB decode, bilinear filtering, ray-plane hits and irradiance integrals are written out
// in this file, independently of shaders/shared):
//   - a plane with a smooth sRGB base-colour texture under a point light: every integrator equals
//     rho(uv)/pi x E per 16x9 block within 1%;
//   - an emissive quad with a smooth texture over a plane: the irradiance equals a midpoint
//     quadrature of the textured radiance (reference and baseline 0.5%, ReSTIR mean of 64 frames
//     1%; blocks 5%);
//   - an alpha-masked quad casts exactly its cut-out shadow and the camera sees through the cut;
//   - the textured G-buffer path on a texture-less material renders bitwise as the untextured one;
//   - a flat normal map leaves the image unchanged, a tilted one matches the tilted closed form.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <functional>
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <optional>
#include <string>
#include <vector>

#include "engine/level/primitives.h"
#include "lighting/integrators/offline_render.h"
#include "lighting/scene/frame_constants.h"
#include "runtime/gpu/shader_library.h"
#include "runtime/image/image_encode.h"
#include "runtime/image/image_io.h"
#include "shared/gbuffer.h"
#include "tests/gbuffer/gbuffer_harness.h"
#include "tests/runtime/gpu_test_support.h"
#include "tests/runtime/scratch_dir.h"
#include "tests/textures/textured_assets.h"

namespace lantern {
namespace {

using lighting::OfflineRenderRequest;
using lighting::VisibilitySetting;

constexpr double kPi = 3.14159265358979323846;
constexpr std::uint32_t kWidth = 64;
constexpr std::uint32_t kHeight = 36;
constexpr std::uint32_t kBlockW = 16;
constexpr std::uint32_t kBlockH = 9;
const glm::vec3 kLightPosition(0.2f, 1.5f, -0.1f);
const glm::vec3 kLightColor(3.0f, 2.0f, 1.0f);

double srgb_decode(double c) {
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

// A decoded 8-bit image as the renderer must see it: linear texels (sRGB decoded or not),
// bilinear with repeat wrap at texel centres.
struct TestTexture {
  std::uint32_t w = 0, h = 0;
  std::vector<glm::dvec4> linear;
  glm::dvec4 bilinear(double u, double v) const {
    const double x = u * w - 0.5, y = v * h - 0.5;
    const double fx = std::floor(x), fy = std::floor(y);
    auto at = [&](long i, long j) {
      const long wi = ((i % static_cast<long>(w)) + w) % w;
      const long hj = ((j % static_cast<long>(h)) + h) % h;
      return linear[static_cast<std::size_t>(hj) * w + static_cast<std::size_t>(wi)];
    };
    const long i = static_cast<long>(fx), j = static_cast<long>(fy);
    const double a = x - fx, b = y - fy;
    return (1 - b) * ((1 - a) * at(i, j) + a * at(i + 1, j)) +
           b * ((1 - a) * at(i, j + 1) + a * at(i + 1, j + 1));
  }
};

TestTexture decode(std::uint32_t w, std::uint32_t h, const std::vector<std::uint8_t>& rgba8,
                   bool srgb) {
  TestTexture t{w, h, {}};
  for (std::size_t i = 0; i < std::size_t{w} * h; ++i) {
    glm::dvec4 c;
    for (int k = 0; k < 4; ++k) c[k] = rgba8[4 * i + static_cast<std::size_t>(k)] / 255.0;
    if (srgb) c = glm::dvec4(srgb_decode(c.r), srgb_decode(c.g), srgb_decode(c.b), c.a);
    t.linear.push_back(c);
  }
  return t;
}

// A smooth colour ramp (8-bit, as stored).
std::vector<std::uint8_t> smooth_rgba8(std::uint32_t w, std::uint32_t h) {
  return test::make_rgba8(w, h, [&](std::uint32_t x, std::uint32_t y) {
    const float u = (x + 0.5f) / static_cast<float>(w), v = (y + 0.5f) / static_cast<float>(h);
    return glm::vec4(0.35f + 0.6f * u, 0.45f + 0.5f * v, 0.6f + 0.3f * u * v, 1.0f);
  });
}

Level base_level(const std::string& name) {
  Level level;
  level.name = name;
  level.meshes.push_back(make_plane(glm::vec2(6.0f, 6.0f)));  // y = 0, facing +Y
  level.camera.position = glm::vec3(0.0f, 4.0f, 0.0f);
  level.camera.orientation = look_at_orientation(level.camera.position, glm::vec3(0.0f));
  level.camera.yfov = 0.7f;
  level.has_camera = true;
  return level;
}

Light point_light() {
  Light light;
  light.color = kLightColor;
  light.position = kLightPosition;
  return light;
}

// make_plane({6, 6})'s texcoords at floor point (x, 0, z): u along +z, v along +x.
glm::dvec2 floor_uv(glm::dvec3 p) {
  return {(p.z + 3.0) / 6.0, (p.x + 3.0) / 6.0};
}

struct Ray {
  glm::dvec3 origin, dir;
};
Ray camera_ray(const Level& level, double x, double y) {
  const glm::mat4 inv = glm::inverse(lighting::camera_view_proj(level.camera, kWidth, kHeight));
  const glm::vec2 ndc =
      glm::vec2(static_cast<float>(x / kWidth), static_cast<float>(y / kHeight)) * 2.0f - 1.0f;
  const glm::vec4 a = inv * glm::vec4(ndc, 0.0f, 1.0f);
  const glm::vec4 b = inv * glm::vec4(ndc, 0.5f, 1.0f);
  return {glm::dvec3(level.camera.position),
          glm::normalize(glm::dvec3(glm::vec3(b) / b.w - glm::vec3(a) / a.w))};
}
glm::dvec3 at_height(const Ray& r, double h) {
  return r.origin + r.dir * ((h - r.origin.y) / r.dir.y);
}

class TextureRenderTest : public runtime::test::GpuTest {
 protected:
  runtime::ImageRGBA32F render(const Level& level, const std::string& integrator,
                               std::uint32_t frames, std::uint32_t seed = 1,
                               std::vector<std::pair<std::string, std::string>> settings = {},
                               VisibilitySetting visibility = VisibilitySetting::Auto) {
    OfflineRenderRequest request;
    request.integrator.name = integrator;
    request.integrator.settings = std::move(settings);
    request.integrator.visibility = visibility;
    if (integrator == "reference") request.integrator.spp = 16;
    request.width = kWidth;
    request.height = kHeight;
    request.frames = frames;
    request.average = true;
    request.animate = false;
    request.seed = seed;
    auto result = lighting::render_offline(device, shaders, level, request);
    EXPECT_EQ(result.images.size(), 1u);
    EXPECT_EQ(result.images[0].count_non_finite(), 0u);
    return result.images[0];
  }
  // The mean of `seeds` renders of `frames` frames.
  runtime::ImageRGBA32F render_mean(const Level& level, const std::string& integrator,
                                    std::uint32_t frames, std::uint32_t seeds) {
    runtime::ImageRGBA32F mean(kWidth, kHeight);
    for (std::uint32_t s = 1; s <= seeds; ++s) {
      const runtime::ImageRGBA32F img = render(level, integrator, frames, s);
      for (std::size_t i = 0; i < mean.pixels.size(); ++i) mean.pixels[i] += img.pixels[i] / seeds;
    }
    return mean;
  }
  runtime::ShaderLibrary shaders;
};

// Compares `image` with `expected` (per pixel rgb; nullopt = not compared) per 16x9 block and
// overall. Returns the number of compared pixels.
int compare_blocks(
    const runtime::ImageRGBA32F& image,
    const std::function<std::optional<glm::dvec3>(std::uint32_t, std::uint32_t)>& expected,
    double block_tolerance, double mean_tolerance, const std::string& what) {
  std::vector<glm::dvec2> blocks((kWidth / kBlockW) * (kHeight / kBlockH), glm::dvec2(0.0));
  glm::dvec2 total(0.0);
  int compared = 0;
  for (std::uint32_t y = 0; y < kHeight; ++y)
    for (std::uint32_t x = 0; x < kWidth; ++x) {
      const std::optional<glm::dvec3> e = expected(x, y);
      if (!e) continue;
      const float* got = image.at(x, y);
      const glm::dvec2 v(static_cast<double>(got[0]) + got[1] + got[2], e->x + e->y + e->z);
      blocks[(y / kBlockH) * (kWidth / kBlockW) + x / kBlockW] += v;
      total += v;
      ++compared;
    }
  for (std::size_t b = 0; b < blocks.size(); ++b) {
    if (blocks[b].y <= 0.0) continue;
    EXPECT_NEAR(blocks[b].x / blocks[b].y, 1.0, block_tolerance) << what << " block " << b;
  }
  std::printf("[textures] %s: mean ratio %.5f over %d pixels\n", what.c_str(), total.x / total.y,
              compared);
  EXPECT_NEAR(total.x / total.y, 1.0, mean_tolerance) << what;
  return compared;
}

// Point light irradiance on the floor (normal n) at p, and the Lambert radiance it gives.
glm::dvec3 point_irradiance(glm::dvec3 p, glm::dvec3 n) {
  const glm::dvec3 to = glm::dvec3(kLightPosition) - p;
  const double d2 = glm::dot(to, to);
  return glm::dvec3(kLightColor) * std::max(0.0, glm::dot(n, to / std::sqrt(d2))) / d2;
}

TEST_F(TextureRenderTest, TexturedPlaneEqualsClosedFormTimesTexture) {
  constexpr std::uint32_t kTex = 32;
  Level level = base_level("textured_plane");
  const std::vector<std::uint8_t> texels = smooth_rgba8(kTex, kTex);
  Material m = make_lambert(1.0f);
  m.base_color_texture.image = test::add_png(level, kTex, kTex, texels);
  level.materials.push_back(m);
  level.instances.push_back(Instance{});
  level.lights.push_back(point_light());
  const TestTexture tex = decode(kTex, kTex, texels, true);
  auto expected = [&](std::uint32_t x, std::uint32_t y) -> std::optional<glm::dvec3> {
    const glm::dvec3 p = at_height(camera_ray(level, x + 0.5, y + 0.5), 0.0);
    const glm::dvec2 uv = floor_uv(p);
    const glm::dvec3 rho = glm::dvec3(tex.bilinear(uv.x, uv.y));
    return rho / kPi * point_irradiance(p, {0, 1, 0});
  };
  for (const char* integrator : {"baseline", "reference", "restir"}) {
    const runtime::ImageRGBA32F image = render(level, integrator, 2);
    EXPECT_EQ(compare_blocks(image, expected, 0.01, 0.01, integrator), int(kWidth * kHeight));
  }
}

// The emitter: a 0.8 m quad at height 1.2 facing down, radiance kFactor x sRGB texture.
constexpr float kQuadHeight = 1.2f;
constexpr float kQuadHalf = 0.4f;
const glm::vec3 kFactor(6.0f, 4.0f, 2.0f);

TEST_F(TextureRenderTest, EmissiveTexturedQuadMatchesQuadrature) {
  constexpr std::uint32_t kTex = 16;
  Level level = base_level("textured_emitter");
  level.meshes.push_back(make_plane(glm::vec2(2.0f * kQuadHalf)));
  level.materials.push_back(make_lambert(0.5f));
  const std::vector<std::uint8_t> texels = smooth_rgba8(kTex, kTex);
  Material emitter = make_lambert(0.0f);
  emitter.emissive_factor = kFactor;
  emitter.emissive_texture.image = test::add_png(level, kTex, kTex, texels);
  level.materials.push_back(emitter);
  level.instances.push_back(Instance{});
  Instance quad;
  quad.mesh = 1;
  quad.material = 1;
  quad.transform.translation = glm::vec3(0.0f, kQuadHeight, 0.0f);
  quad.transform.rotation = glm::angleAxis(glm::pi<float>(), glm::vec3(1, 0, 0));
  quad.world = quad.transform.matrix();
  level.instances.push_back(quad);
  const TestTexture tex = decode(kTex, kTex, texels, true);

  // Midpoint quadrature over the quad: world (x, h, z) has local (x, 0, -z), uv ((0.4 - z) / 0.8,
  // (x + 0.4) / 0.8); both cosines are h / d.
  constexpr int kCells = 96;
  const double cell = 2.0 * kQuadHalf / kCells;
  std::vector<glm::dvec3> radiance(kCells * kCells);
  std::vector<glm::dvec2> position(kCells * kCells);
  for (int i = 0; i < kCells; ++i)
    for (int j = 0; j < kCells; ++j) {
      const double x = -kQuadHalf + (i + 0.5) * cell, z = -kQuadHalf + (j + 0.5) * cell;
      const glm::dvec4 t =
          tex.bilinear((kQuadHalf - z) / (2 * kQuadHalf), (x + kQuadHalf) / (2 * kQuadHalf));
      radiance[static_cast<std::size_t>(i * kCells + j)] = glm::dvec3(kFactor) * glm::dvec3(t);
      position[static_cast<std::size_t>(i * kCells + j)] = {x, z};
    }
  auto expected = [&](std::uint32_t x, std::uint32_t y) -> std::optional<glm::dvec3> {
    for (const glm::dvec2 d : {glm::dvec2(0.5), glm::dvec2(0, 0), glm::dvec2(1, 0),
                               glm::dvec2(0, 1), glm::dvec2(1, 1)}) {
      const glm::dvec3 q = at_height(camera_ray(level, x + d.x, y + d.y), kQuadHeight);
      if (std::abs(q.x) <= kQuadHalf + 1e-3 && std::abs(q.z) <= kQuadHalf + 1e-3)
        return std::nullopt;
    }
    const glm::dvec3 p = at_height(camera_ray(level, x + 0.5, y + 0.5), 0.0);
    glm::dvec3 e(0.0);
    for (std::size_t k = 0; k < radiance.size(); ++k) {
      const glm::dvec3 to(position[k].x - p.x, kQuadHeight, position[k].y - p.z);
      const double d2 = glm::dot(to, to);
      e += radiance[k] * (kQuadHeight * kQuadHeight / (d2 * d2));
    }
    return 0.5 / kPi * e * (cell * cell);
  };
  compare_blocks(render(level, "reference", 16), expected, 0.05, 0.005, "reference");
  compare_blocks(render(level, "baseline", 64), expected, 0.05, 0.005, "baseline");
  compare_blocks(render_mean(level, "restir", 16, 4), expected, 0.05, 0.01,
                 "restir (4 x 16 frames)");
}

// The floor instance (mesh 0, material 0) and an alpha-masked quad (mesh 1, a 1 m plane the
// caller added) at `height`: its material's 8x8 texture is opaque for x < 4 (u < 0.5, world
// z < 0) and cut out elsewhere (nearest sampling, cutoff 0.5); the mask is material 1.
void add_floor_and_masked_quad(Level& level, double height) {
  Material mask = make_lambert(0.3f);
  mask.alpha_mode = AlphaMode::Mask;
  mask.alpha_cutoff = 0.5f;
  mask.base_color_texture.sampler.mag_linear = false;
  mask.base_color_texture.image =
      test::add_png(level, 8, 8, test::make_rgba8(8, 8, [](std::uint32_t x, std::uint32_t) {
                      return glm::vec4(1.0f, 1.0f, 1.0f, x < 4 ? 1.0f : 0.0f);
                    }));
  level.materials.push_back(mask);
  level.instances.push_back(Instance{});
  Instance quad;
  quad.mesh = 1;
  quad.material = 1;
  quad.transform.translation = glm::vec3(0.0f, static_cast<float>(height), 0.0f);
  quad.world = quad.transform.matrix();
  level.instances.push_back(quad);
}

// An alpha-masked 1 m quad at height 0.75 under a point light at (0, 1.5, 0): its texels with
// z < 0 (u < 0.5) are opaque, the rest cut out (nearest sampling, cutoff 0.5).
TEST_F(TextureRenderTest, AlphaCutoutCastsTheCutOutShadow) {
  constexpr double kOccluderY = 0.75;
  Level level = base_level("alpha_cutout");
  level.meshes.push_back(make_plane(glm::vec2(1.0f, 1.0f)));
  level.materials.push_back(make_lambert(0.5f));
  add_floor_and_masked_quad(level, kOccluderY);
  Light light = point_light();
  light.position = glm::vec3(0.0f, 1.5f, 0.0f);
  level.lights.push_back(light);
  const glm::dvec3 lp(light.position);

  // The opaque half of the occluder: |x| <= 0.5, -0.5 <= z < 0.
  auto opaque = [](glm::dvec3 q) { return std::abs(q.x) <= 0.5 && q.z >= -0.5 && q.z < 0.0; };
  auto shadowed = [&](glm::dvec3 p) {
    const glm::dvec3 q = p + (lp - p) * ((kOccluderY - p.y) / (lp.y - p.y));
    return opaque(q);
  };
  int through_cut = 0, shadow = 0;
  auto expected = [&](std::uint32_t x, std::uint32_t y) -> std::optional<glm::dvec3> {
    bool first = true, state_blocked = false, state_shadow = false;
    for (const glm::dvec2 d : {glm::dvec2(0.5), glm::dvec2(0, 0), glm::dvec2(1, 0),
                               glm::dvec2(0, 1), glm::dvec2(1, 1)}) {
      const Ray r = camera_ray(level, x + d.x, y + d.y);
      const bool blocked = opaque(at_height(r, kOccluderY));
      const bool s = shadowed(at_height(r, 0.0));
      if (!first && (blocked != state_blocked || s != state_shadow)) return std::nullopt;  // edge
      first = false;
      state_blocked = blocked;
      state_shadow = s;
    }
    if (state_blocked) return std::nullopt;  // the camera sees the opaque half
    const Ray r = camera_ray(level, x + 0.5, y + 0.5);
    const glm::dvec3 q = at_height(r, kOccluderY);
    if (std::abs(q.x) <= 0.5 && std::abs(q.z) <= 0.5) ++through_cut;  // seen through the cut
    const glm::dvec3 p = at_height(r, 0.0);
    if (state_shadow) {
      ++shadow;
      return glm::dvec3(0.0);
    }
    const glm::dvec3 to = lp - p;
    const double d2 = glm::dot(to, to);
    return 0.5 / kPi * glm::dvec3(kLightColor) * (to.y / std::sqrt(d2)) / d2;
  };
  struct Run {
    const char* integrator;
    VisibilitySetting visibility;
  };
  for (const Run run : {Run{"baseline", VisibilitySetting::Bvh}, Run{"restir", VisibilitySetting::Bvh},
                        Run{"baseline", VisibilitySetting::RayQuery}}) {
    if (run.visibility == VisibilitySetting::RayQuery && !device.caps().ray_query) continue;
    const char* integrator = run.integrator;
    const runtime::ImageRGBA32F image = render(level, integrator, 2, 1, {}, run.visibility);
    through_cut = shadow = 0;
    for (std::uint32_t y = 0; y < kHeight; ++y)
      for (std::uint32_t x = 0; x < kWidth; ++x) {
        const std::optional<glm::dvec3> e = expected(x, y);
        if (!e) continue;
        for (int k = 0; k < 3; ++k)
          EXPECT_NEAR(image.at(x, y)[k], (*e)[k], 2e-3 * (*e)[k] + 1e-6)
              << integrator << " pixel (" << x << ", " << y << ") channel " << k;
      }
    EXPECT_GE(through_cut, 60) << "pixels that see the floor through the cut-out half";
    EXPECT_GE(shadow, 60) << "pixels in the opaque half's shadow";
  }
}

// A level with a material texture the visible materials do not use compiles the textured
// G-buffer path (kTextured) and textured light evaluation in: the image must not change by a bit.
TEST_F(TextureRenderTest, TexturedPathIsBitwiseNeutralForUntexturedMaterials) {
  Level level = base_level("untextured");
  level.meshes.push_back(make_plane(glm::vec2(0.8f)));
  level.materials.push_back(make_lambert(0.5f));
  Material glow = make_lambert(0.0f);
  glow.emissive_factor = kFactor;
  level.materials.push_back(glow);
  level.instances.push_back(Instance{});
  Instance quad;
  quad.mesh = 1;
  quad.material = 1;
  quad.transform.translation = glm::vec3(0.0f, kQuadHeight, 0.0f);
  quad.transform.rotation = glm::angleAxis(glm::pi<float>(), glm::vec3(1, 0, 0));
  quad.world = quad.transform.matrix();
  level.instances.push_back(quad);
  level.lights.push_back(point_light());
  Level with_texture = level;
  Material unused = make_lambert(1.0f);
  unused.base_color_texture.image = test::add_png(with_texture, 4, 4, smooth_rgba8(4, 4));
  with_texture.materials.push_back(unused);
  for (const char* integrator : {"baseline", "restir"}) {
    const runtime::ImageRGBA32F a = render(level, integrator, 2);
    const runtime::ImageRGBA32F b = render(with_texture, integrator, 2);
    ASSERT_EQ(a.pixels.size(), b.pixels.size());
    std::size_t differing = 0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i)
      differing += std::memcmp(&a.pixels[i], &b.pixels[i], sizeof(float)) != 0 ? 1 : 0;
    EXPECT_EQ(differing, 0u) << integrator;
  }
}

// Normal maps on the plane (tangent +z world = +u, bitangent -x world: glTF's +Y "up" is -v).
TEST_F(TextureRenderTest, FlatNormalMapIsNeutralTiltedMatchesClosedForm) {
  auto level_with = [&](std::optional<std::vector<std::uint8_t>> normal_exr_or_png, bool exr,
                        std::uint32_t size) {
    Level level = base_level("normal_map");
    Material m = make_lambert(0.5f);
    if (normal_exr_or_png) {
      ImageRef ref;
      ref.name = "normal";
      ref.mime_type = exr ? "image/x-exr" : "image/png";
      ref.embedded = *normal_exr_or_png;
      level.images.push_back(ref);
      m.normal_texture.image = 0;
      (void)size;
    }
    level.materials.push_back(m);
    level.instances.push_back(Instance{});
    level.lights.push_back(point_light());
    return level;
  };
  auto constant_exr = [](glm::vec3 n) {
    std::vector<float> texels;
    for (int i = 0; i < 16; ++i)
      texels.insert(texels.end(), {0.5f * n.x + 0.5f, 0.5f * n.y + 0.5f, 0.5f * n.z + 0.5f, 1.0f});
    return runtime::encode_exr(4, 4, texels);
  };
  const runtime::ImageRGBA32F plain = render(level_with(std::nullopt, false, 0), "baseline", 1);
  // Flat, exactly representable in half floats: the same image up to rounding.
  const runtime::ImageRGBA32F flat =
      render(level_with(constant_exr({0, 0, 1}), true, 4), "baseline", 1);
  // Flat in 8 bits: (128, 128, 255) is 0.4% off (0, 0, 1).
  const runtime::ImageRGBA32F flat8 = render(
      level_with(test::png_of(4, 4,
                              test::make_rgba8(4, 4,
                                               [](auto, auto) {
                                                 return glm::vec4(128 / 255.0f, 128 / 255.0f, 1, 1);
                                               })),
                 false, 4),
      "baseline", 1);
  double worst = 0.0, worst8 = 0.0;
  for (std::size_t i = 0; i < plain.pixels.size(); ++i) {
    if (i % 4 == 3 || !(plain.pixels[i] > 0.0f)) continue;
    worst = std::max(worst, std::abs(double(flat.pixels[i]) / plain.pixels[i] - 1.0));
    worst8 = std::max(worst8, std::abs(double(flat8.pixels[i]) / plain.pixels[i] - 1.0));
  }
  std::printf("[textures] flat normal map: worst pixel %.2e (half), %.2e (8-bit)\n", worst, worst8);
  EXPECT_LE(worst, 1e-5);
  EXPECT_LE(worst8, 2e-2);

  // Tilted by 30 degrees towards +u (world +z): n' = (0, cos, sin).
  const double a = 30.0 * kPi / 180.0;
  const Level tilted_level =
      level_with(constant_exr(glm::vec3(static_cast<float>(std::sin(a)), 0.0f,
                                        static_cast<float>(std::cos(a)))),
                 true, 4);
  const glm::dvec3 n(0.0, std::cos(a), std::sin(a));
  auto expected = [&](std::uint32_t x, std::uint32_t y) -> std::optional<glm::dvec3> {
    const Ray r = camera_ray(tilted_level, x + 0.5, y + 0.5);
    const glm::dvec3 p = at_height(r, 0.0);
    const glm::dvec3 to = glm::dvec3(kLightPosition) - p;
    const double d2 = glm::dot(to, to);
    const double cos_n = glm::dot(n, to / std::sqrt(d2));
    if (cos_n < 0.05 || glm::dot(n, -r.dir) < 0.05) return std::nullopt;  // near the terminator
    return 0.5 / kPi * glm::dvec3(kLightColor) * cos_n / d2;
  };
  const runtime::ImageRGBA32F tilted = render(tilted_level, "baseline", 1);
  compare_blocks(tilted, expected, 0.01, 0.01, "tilted normal map");
  // And it differs from the untilted plane (the tilt is visible).
  double change = 0.0, total = 0.0;
  for (std::size_t i = 0; i < plain.pixels.size(); ++i) {
    if (i % 4 == 3) continue;
    change += std::abs(double(tilted.pixels[i]) - plain.pixels[i]);
    total += plain.pixels[i];
  }
  EXPECT_GT(change, 0.1 * total);
}

// The asset's vertex tangents orient the normal map: tangent +x world with w = -1 makes the
// map's +Y ("up" = w cross(n, t)) world +z, so a map tilted 30 degrees towards +Y gives the
// closed form with n' = (0, cos, sin); the triangle's own frame (up = -x) would tilt towards -x,
// and ignoring w towards -z.
TEST_F(TextureRenderTest, AssetTangentsOrientTheNormalMap) {
  const double a = 30.0 * kPi / 180.0;
  std::vector<float> texels;
  for (int i = 0; i < 16; ++i)
    texels.insert(texels.end(), {0.5f, 0.5f * static_cast<float>(std::sin(a)) + 0.5f,
                                 0.5f * static_cast<float>(std::cos(a)) + 0.5f, 1.0f});
  Level level = base_level("asset_tangents");
  ImageRef ref;
  ref.name = "normal";
  ref.mime_type = "image/x-exr";
  ref.embedded = runtime::encode_exr(4, 4, texels);
  level.images.push_back(ref);
  Material m = make_lambert(0.5f);
  m.normal_texture.image = 0;
  level.materials.push_back(m);
  level.instances.push_back(Instance{});
  level.lights.push_back(point_light());
  Mesh& plane = level.meshes[0];
  plane.tangents.assign(plane.positions.size(), glm::vec4(1.0f, 0.0f, 0.0f, -1.0f));
  const glm::dvec3 n(0.0, std::cos(a), std::sin(a));
  auto expected = [&](std::uint32_t x, std::uint32_t y) -> std::optional<glm::dvec3> {
    const Ray r = camera_ray(level, x + 0.5, y + 0.5);
    const glm::dvec3 p = at_height(r, 0.0);
    const glm::dvec3 to = glm::dvec3(kLightPosition) - p;
    const double d2 = glm::dot(to, to);
    const double cos_n = glm::dot(n, to / std::sqrt(d2));
    if (cos_n < 0.05 || glm::dot(n, -r.dir) < 0.05) return std::nullopt;  // near the terminator
    return 0.5 / kPi * glm::dvec3(kLightColor) * cos_n / d2;
  };
  compare_blocks(render(level, "baseline", 1), expected, 0.01, 0.01, "asset tangents");

  // Both G-buffer methods write that shading normal (the forward pass finds the fragment's
  // barycentrics for the vertex tangents itself).
  const lighting::SceneData scene = lighting::build_scene_data(level);
  const gpu::FrameConstants fc =
      lighting::make_frame_constants(level.camera, kWidth, kHeight, 0, 1, {});
  for (const lighting::GBufferMethod method :
       {lighting::GBufferMethod::Forward, lighting::GBufferMethod::Visibility}) {
    test::GBufferHarness harness(device, shaders, scene, {.method = method});
    const test::GBufferImages g = *harness.render(fc, true);
    double worst = 0.0;
    std::size_t seen = 0;
    for (std::size_t i = 0; i < g.normal.size(); ++i) {
      if (g.ids[i].x != 0u) continue;  // not the plane
      const glm::vec3 shading = gpu::oct_decode(glm::vec2(g.normal[i].x, g.normal[i].y));
      worst = std::max(worst, glm::length(glm::dvec3(shading) - n));
      ++seen;
    }
    EXPECT_GT(seen, g.normal.size() / 2);
    EXPECT_LE(worst, 1e-3) << "method " << static_cast<int>(method);
  }
}

// A material mixing texcoord sets: base colour on TEXCOORD_1 (the floor's uvs swapped), emission
// on TEXCOORD_0. Both G-buffer methods sample each texture at its own set's uv (closed form,
// half precision).
TEST_F(TextureRenderTest, TexturesSampleTheirOwnTexcoordSet) {
  constexpr std::uint32_t kTex = 32;
  Level level = base_level("texcoord_sets");
  Mesh& floor_mesh = level.meshes[0];
  for (const glm::vec2& uv : floor_mesh.uvs) floor_mesh.uvs1.emplace_back(uv.y, uv.x);
  const std::vector<std::uint8_t> albedo_texels = smooth_rgba8(kTex, kTex);
  const std::vector<std::uint8_t> emission_texels =
      test::make_rgba8(kTex, kTex, [&](std::uint32_t x, std::uint32_t y) {
        const float u = (x + 0.5f) / kTex, v = (y + 0.5f) / kTex;
        return glm::vec4(0.2f + 0.7f * v, 0.3f + 0.2f * u, 0.9f - 0.5f * u, 1.0f);
      });
  Material m = make_lambert(1.0f);
  m.base_color_texture.image = test::add_png(level, kTex, kTex, albedo_texels);
  m.base_color_texture.texcoord = 1;
  m.emissive_factor = glm::vec3(1.0f);
  m.emissive_texture.image = test::add_png(level, kTex, kTex, emission_texels);
  level.materials.push_back(m);
  level.instances.push_back(Instance{});
  const TestTexture albedo = decode(kTex, kTex, albedo_texels, true);
  const TestTexture emission = decode(kTex, kTex, emission_texels, true);
  const lighting::SceneData scene = lighting::build_scene_data(level);
  ASSERT_EQ(scene.vertex_texcoords1.size(), scene.vertices.size());
  const gpu::FrameConstants fc =
      lighting::make_frame_constants(level.camera, kWidth, kHeight, 0, 1, {});
  for (const lighting::GBufferMethod method :
       {lighting::GBufferMethod::Forward, lighting::GBufferMethod::Visibility}) {
    test::GBufferHarness harness(device, shaders, scene, {.method = method});
    const test::GBufferImages g = *harness.render(fc, true);
    std::size_t checked = 0;
    double worst_albedo = 0.0, worst_emission = 0.0;
    for (std::uint32_t y = 0; y < kHeight; ++y)
      for (std::uint32_t x = 0; x < kWidth; ++x) {
        const std::size_t i = g.index(x, y);
        if (g.ids[i].x != 0u) continue;
        const glm::dvec2 uv0 = floor_uv(at_height(camera_ray(level, x + 0.5, y + 0.5), 0.0));
        const glm::dvec3 rho(albedo.bilinear(uv0.y, uv0.x));
        const glm::dvec3 le(emission.bilinear(uv0.x, uv0.y));
        for (int k = 0; k < 3; ++k) {
          worst_albedo = std::max(worst_albedo, std::abs(g.albedo_roughness[i][k] - rho[k]) / rho[k]);
          worst_emission =
              std::max(worst_emission, std::abs(g.emission_metallic[i][k] - le[k]) / le[k]);
        }
        ++checked;
      }
    std::printf("[textures] texcoord sets (method %d): %zu pixels, worst albedo %.2e, emission %.2e\n",
                static_cast<int>(method), checked, worst_albedo, worst_emission);
    EXPECT_GT(checked, std::size_t{kWidth} * kHeight / 2);
    EXPECT_LE(worst_albedo, 3e-3);
    EXPECT_LE(worst_emission, 3e-3);
  }
}

// Both G-buffer methods on textured, alpha-masked content: the albedo is the sRGB-decoded texture
// at the pixel's texcoord (closed form, half precision), and the camera sees the floor through
// the cut-out half of a masked quad (ids) and the quad's opaque half elsewhere.
TEST_F(TextureRenderTest, BothGBufferMethodsSampleTexturesAndCutOut) {
  constexpr std::uint32_t kTex = 32;
  constexpr double kQuadY = 1.0;
  Level level = base_level("gbuffer_methods");
  level.meshes.push_back(make_plane(glm::vec2(1.0f, 1.0f)));
  const std::vector<std::uint8_t> texels = smooth_rgba8(kTex, kTex);
  Material floor = make_lambert(1.0f);
  floor.base_color_texture.image = test::add_png(level, kTex, kTex, texels);
  level.materials.push_back(floor);
  add_floor_and_masked_quad(level, kQuadY);
  const TestTexture tex = decode(kTex, kTex, texels, true);
  const lighting::SceneData scene = lighting::build_scene_data(level);
  const gpu::FrameConstants fc =
      lighting::make_frame_constants(level.camera, kWidth, kHeight, 0, 1, {});
  std::vector<test::GBufferImages> images;
  for (const lighting::GBufferMethod method :
       {lighting::GBufferMethod::Forward, lighting::GBufferMethod::Visibility}) {
    test::GBufferHarness harness(device, shaders, scene, {.method = method});
    images.push_back(*harness.render(fc, true));
  }
  int floor_pixels = 0, through_cut = 0, opaque = 0;
  for (std::uint32_t y = 0; y < kHeight; ++y)
    for (std::uint32_t x = 0; x < kWidth; ++x) {
      // Skip pixels whose footprint straddles the quad's outline or its alpha edge (z = 0).
      int state = -1;
      bool edge = false;
      for (const glm::dvec2 d : {glm::dvec2(0.5), glm::dvec2(0, 0), glm::dvec2(1, 0),
                                 glm::dvec2(0, 1), glm::dvec2(1, 1)}) {
        const glm::dvec3 q = at_height(camera_ray(level, x + d.x, y + d.y), kQuadY);
        const bool inside = std::abs(q.x) <= 0.5 && std::abs(q.z) <= 0.5;
        const int s = !inside ? 0 : (q.z < 0.0 ? 2 : 1);  // 0 outside, 1 cut out, 2 opaque
        edge = edge || (state >= 0 && s != state);
        state = s;
      }
      if (edge) continue;
      const glm::dvec3 p = at_height(camera_ray(level, x + 0.5, y + 0.5), 0.0);
      const glm::dvec2 uv = floor_uv(p);
      const glm::dvec3 rho(tex.bilinear(uv.x, uv.y));
      for (std::size_t m = 0; m < images.size(); ++m) {
        const test::GBufferImages& g = images[m];
        const std::size_t i = g.index(x, y);
        if (state == 2) {
          EXPECT_EQ(g.ids[i].x, 1u) << "method " << m << " pixel " << x << "," << y;
          continue;
        }
        EXPECT_EQ(g.ids[i].x, 0u) << "method " << m << " pixel " << x << "," << y;
        for (int k = 0; k < 3; ++k)
          EXPECT_NEAR(g.albedo_roughness[i][k], rho[k], 2e-3 * rho[k] + 1e-4)
              << "method " << m << " pixel " << x << "," << y << " channel " << k;
      }
      (state == 2 ? opaque : state == 1 ? through_cut : floor_pixels)++;
    }
  EXPECT_GE(through_cut, 100);
  EXPECT_GE(opaque, 100);
  EXPECT_GE(floor_pixels, 300);
}

// The environment map convention (docs/levels.md) is Blender's world texture: a map whose four
// column quadrants (and two halves, top and bottom) differ in colour, seen along directions
// computed here from Cycles' equirectangular formula (u = 1/2 - atan2(y, x) / 2pi, v from the
// bottom = 1 - acos(z) / pi, in Blender's Z-up axes = our (x, -z, y)); rotation_deg turns the map
// in the world (map_to_world = R).
TEST_F(TextureRenderTest, EnvironmentQuadrantsFollowBlendersConvention) {
  const glm::dvec3 quadrant[4] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 0}};
  runtime::ImageRGBA32F map(16, 8);
  for (std::uint32_t y = 0; y < 8; ++y)
    for (std::uint32_t x = 0; x < 16; ++x) {
      const glm::dvec3 c = quadrant[x / 4] * (y < 4 ? 1.0 : 0.25);
      float* p = map.at(x, y);
      p[0] = static_cast<float>(c.r);
      p[1] = static_cast<float>(c.g);
      p[2] = static_cast<float>(c.b);
      p[3] = 1.0f;
    }
  const auto& dir = lantern::test::process_scratch_dir();
  runtime::write_image(dir / "quadrants.exr", map);
  // Blender's (u, v-from-top) -> our world direction (map not rotated).
  auto blender_direction = [](double u, double v_top) {
    const double a = 2.0 * kPi * (0.5 - u);  // atan2(b.y, b.x)
    const double polar = v_top * kPi;        // acos(b.z)
    const glm::dvec3 b(std::sin(polar) * std::cos(a), std::sin(polar) * std::sin(a),
                       std::cos(polar));
    return glm::dvec3(b.x, b.z, -b.y);
  };
  for (const float yaw_deg : {0.0f, 90.0f}) {
    const glm::quat rotation = glm::quat(glm::radians(glm::vec3(0.0f, yaw_deg, 0.0f)));
    for (int q = 0; q < 4; ++q)
      for (const double v_top : {0.35, 0.65}) {
        const glm::dvec3 map_dir = blender_direction(0.125 + 0.25 * q, v_top);
        const glm::dvec3 world_dir = glm::dquat(rotation) * map_dir;
        Level level;
        level.name = "quadrants";
        level.meshes.push_back(make_plane(glm::vec2(1.0f)));
        level.materials.push_back(make_lambert(0.5f));
        Instance far_below;
        far_below.transform.translation = glm::vec3(0.0f, -500.0f, 0.0f);
        far_below.world = far_below.transform.matrix();
        level.instances.push_back(far_below);
        level.environment = EnvironmentMap{dir / "quadrants.exr", 1.0f, rotation};
        level.camera.position = glm::vec3(0.0f);
        level.camera.orientation = look_at_orientation(glm::vec3(0.0f), glm::vec3(world_dir));
        level.camera.yfov = 0.3f;
        level.has_camera = true;
        const runtime::ImageRGBA32F image = render(level, "baseline", 1);
        const glm::dvec3 expected = quadrant[q] * (v_top < 0.5 ? 1.0 : 0.25);
        const float* got = image.at(kWidth / 2, kHeight / 2);
        for (int k = 0; k < 3; ++k)
          EXPECT_NEAR(got[k], expected[k], 1e-4)
              << "yaw " << yaw_deg << " quadrant " << q << " v " << v_top << " channel " << k;
      }
  }
}

}  // namespace
}  // namespace lantern
