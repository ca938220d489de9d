// Emitters in the denoiser: filtered for the light they reflect (their emission exact, no light
// across their edge), a lone sample on one clamped, passed through when the level has media.
#include "tests/denoise/denoise_gpu_fixture.h"

namespace lantern::denoise_test {
namespace {

// The denoise corner with an emitting panel on the wall beside the box (1 mm in front of it, the
// same plane to the edge stops; emission 4, base colour grey as the wall's), and with a volume of
// zero density too (media: the image reaching the denoiser is still the test's own).
std::string emitter_corner_json(bool media) {
  std::string json = kScene;
  const std::string grey = R"("grey": { "base_color": [0.5, 0.5, 0.5], "roughness": 0.8 })";
  json.insert(json.find(grey) + grey.size(), R"(, "lamp": { "base_color": [0.5, 0.5, 0.5],
    "roughness": 0.8, "emissive": [1, 1, 1], "emissive_strength": 4 })");
  const std::string primitives = R"("primitives": [)";
  json.insert(json.find(primitives) + primitives.size(), R"(
    { "type": "plane", "name": "panel", "size": [1.2, 1.2], "material": "lamp",
      "translation": [1.4, 1.0, -1.999], "rotation_deg": [90, 0, 0] },)");
  if (media) {
    json.insert(json.rfind('}'), R"(, "volumes": [ { "name": "fog", "generate": {
      "type": "constant", "size": [2, 2, 2], "voxel_size": 0.5 }, "density_scale": 0.0 } ])");
  }
  return json;
}

// An image of the G-buffer's emission plus `reflected(pixel, emitter)` on every surface pixel
// (alpha 1; the sky black), and the emitter pixels' mask.
template <class Reflected>
ImageRGBA32F emission_plus(const lighting::GBufferTexels& g, Reflected reflected,
                           std::vector<std::uint8_t>* emitters = nullptr) {
  ImageRGBA32F image(g.width, g.height);
  if (emitters) emitters->assign(g.emission.size(), 0);
  for (std::size_t p = 0; p < g.emission.size(); ++p) {
    image.pixels[4 * p + 3] = 1.0f;
    if (g.ids[p].x == gpu::kNoInstance) continue;
    const glm::vec3 e(g.emission[p]);
    const bool emitter = glm::any(glm::greaterThan(e, glm::vec3(0.0f)));
    if (emitters) (*emitters)[p] = emitter ? 1 : 0;
    for (int k = 0; k < 3; ++k) image.pixels[4 * p + k] = e[k] + reflected(p, k, emitter);
  }
  return image;
}

class DenoiseEmitterTest : public DenoiseGpuTest {
 protected:
  std::shared_ptr<const Level> lamp =
      test::level_from_json("denoise_lamp", emitter_corner_json(false));
  std::shared_ptr<const Level> foggy_lamp =
      test::level_from_json("denoise_lamp_fog", emitter_corner_json(true));

  std::unique_ptr<RenderHarness> harness(
      std::shared_ptr<const Level> scene, ImageIntegrator*& input,
      const std::vector<std::pair<std::string, std::string>>& denoise = {}) {
    auto integrator = std::make_unique<ImageIntegrator>(device, kW, kH);
    input = integrator.get();
    auto h = std::make_unique<RenderHarness>(device, shaders, scene, std::move(integrator), kW, kH);
    h->renderer().set_output(lighting::FrameOutput::Denoised);
    h->renderer().set_denoise_settings(lighting::make_denoise_settings("balanced", denoise));
    return h;
  }
  // The still view's G-buffer (one black frame).
  lighting::GBufferTexels gbuffer(std::shared_ptr<const Level> scene) {
    ImageIntegrator* input = nullptr;
    auto h = harness(scene, input);
    input->set(constant(0.0f));
    lighting::GBufferTexels g;
    (void)h->render(test::first_snapshot(scene, kW, kH), &g);
    return g;
  }
};

// An emitter is filtered for the light it reflects: 16 frames of its emission plus noise of mean
// 10 c (the walls: noise of mean c) keep the reflected light's mean on the panel (within 2%) while
// its variance drops at least 10x, as on any surface (passed through, it kept its noise), and the
// wall within 2 pixels of it keeps its mean within 3%. (With the panel and the wall one kind to
// the filter, the wall's light pulled the panel's reflected mean 6.5% low.)
TEST_F(DenoiseEmitterTest, EmittersAreFilteredForTheLightTheyReflect) {
  const lighting::GBufferTexels g = gbuffer(lamp);
  std::vector<std::uint8_t> emitters;
  const float c = 0.37f;
  auto noise = [&](std::uint32_t f) {
    const ImageRGBA32F n = noisy(c, f);
    return emission_plus(
        g, [&](std::size_t p, int k, bool e) { return (e ? 10.0f : 1.0f) * n.pixels[4 * p + k]; },
        &emitters);
  };
  ImageIntegrator* input = nullptr;
  auto h = harness(lamp, input);
  FrameSnapshot s = test::first_snapshot(lamp, kW, kH);
  ImageRGBA32F out;
  for (std::uint32_t f = 0; f < 16; ++f) {
    if (f > 0) s = frozen(s);
    input->set(noise(f));
    out = h->render(s);
  }
  ASSERT_GT(test::count(emitters), 100u) << "the view shows the emitting panel";
  // Wall pixels within 2 pixels of the panel.
  const std::vector<std::uint8_t> mask = surfaces(g);
  std::vector<std::uint8_t> beside(mask.size(), 0);
  for (std::uint32_t y = 2; y + 2 < kH; ++y) {
    for (std::uint32_t x = 2; x + 2 < kW; ++x) {
      const std::size_t p = std::size_t{y} * kW + x;
      if (!mask[p] || emitters[p]) continue;
      for (int dy = -2; dy <= 2; ++dy)
        for (int dx = -2; dx <= 2; ++dx) beside[p] |= emitters[p + dy * int{kW} + dx];
    }
  }
  ASSERT_GT(test::count(beside), 50u);
  const ImageRGBA32F in = noise(15);
  const float r = 10.0f * c;
  double reflected = 0.0, var_out = 0.0, var_in = 0.0;
  for (std::size_t p = 0; p < emitters.size(); ++p) {
    if (!emitters[p]) continue;
    for (int k = 0; k < 3; ++k) {
      const double e = g.emission[p][k];
      reflected += out.pixels[4 * p + k] - e;
      var_out += std::pow(out.pixels[4 * p + k] - e - r, 2.0);
      var_in += std::pow(in.pixels[4 * p + k] - e - r, 2.0);
    }
  }
  reflected /= 3.0 * static_cast<double>(test::count(emitters));
  const double beside_mean = test::masked_mean(out, beside);
  std::printf(
      "[denoise emitters] reflected mean %.5f (true %.5f), variance in %.3g out %.3g; "
      "wall beside the panel %.5f (true %.5f)\n",
      reflected, r, var_in, var_out, beside_mean, c);
  EXPECT_NEAR(reflected / r, 1.0, 0.02);
  EXPECT_GT(var_in / var_out, 10.0);
  EXPECT_NEAR(beside_mean / c, 1.0, 0.03);
}

// Light does not cross between an emitter and the surfaces around it, either way: a still view
// of the panel at its emission plus 10 c of reflected light beside walls at c comes out exactly so
// on every pixel (first frame and three more: temporal, variance, à-trous and stabilisation).
// An emitter's emission is exact: with no reflected light it comes out as the G-buffer's.
TEST_F(DenoiseEmitterTest, EmissionIsExactAndLightDoesNotCrossTheEmittersEdge) {
  const lighting::GBufferTexels g = gbuffer(lamp);
  const float c = 0.3f;
  for (const float r : {10.0f * c, 0.0f}) {
    SCOPED_TRACE("reflected on the box " + std::to_string(r));
    std::vector<std::uint8_t> emitters;
    const ImageRGBA32F input_image = emission_plus(
        g, [&](std::size_t, int, bool emitter) { return emitter ? r : c; }, &emitters);
    ImageIntegrator* input = nullptr;
    auto h = harness(lamp, input);
    input->set(input_image);
    FrameSnapshot s = test::first_snapshot(lamp, kW, kH);
    const std::vector<std::uint8_t> mask = surfaces(g);
    for (int f = 0; f < 4; ++f) {
      if (f > 0) s = frozen(s);
      const ImageRGBA32F out = h->render(s);
      float worst = 0.0f;
      for (std::size_t p = 0; p < mask.size(); ++p) {
        if (!mask[p]) continue;
        const float want = input_image.pixels[4 * p];
        worst = std::max(worst, std::abs(out.pixels[4 * p] - want) / want);
      }
      EXPECT_LT(worst, 1e-5f) << "frame " << f;
    }
  }
}

// A lone heavy sample on an emitter with no history to judge it (the first frame, temporal only)
// is clamped like one on any surface, against its brightest emitter neighbour: emission + 2 c
// (the balanced preset's neighbour_clamp 2) where the panel reflects c and this pixel reported
// 100 c; the walls (at c, but never an emitter's neighbour for the clamp) stay c.
TEST_F(DenoiseEmitterTest, LoneSampleOnAnEmitterIsClamped) {
  const lighting::GBufferTexels g = gbuffer(lamp);
  const float c = 0.3f;
  std::vector<std::uint8_t> emitters;
  ImageRGBA32F input_image = emission_plus(
      g, [&](std::size_t, int, bool) { return c; }, &emitters);
  // An emitter pixel whose 8 neighbours are emitters.
  std::size_t spike = 0;
  for (std::uint32_t y = 1; y + 1 < kH && spike == 0; ++y) {
    for (std::uint32_t x = 1; x + 1 < kW && spike == 0; ++x) {
      bool all = true;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) all = all && emitters[(y + dy) * kW + (x + dx)];
      if (all) spike = std::size_t{y} * kW + x;
    }
  }
  ASSERT_NE(spike, 0u);
  for (int k = 0; k < 3; ++k) input_image.pixels[4 * spike + k] += 99.0f * c;
  ImageIntegrator* input = nullptr;
  auto h = harness(lamp, input, {{"atrous", "0"}});
  input->set(input_image);
  const ImageRGBA32F out = h->render(test::first_snapshot(lamp, kW, kH));
  const float expected = g.emission[spike].x + 2.0f * c;
  std::printf("[denoise emitter clamp] spike %.5f (expected %.5f)\n", out.pixels[4 * spike],
              expected);
  EXPECT_NEAR(out.pixels[4 * spike], expected, 1e-4f * expected);
  std::vector<std::uint8_t> others = surfaces(g);
  others[spike] = 0;
  for (std::size_t p = 0; p < others.size(); ++p) {
    if (!others[p]) continue;
    EXPECT_NEAR(out.pixels[4 * p], input_image.pixels[4 * p], 1e-5f * input_image.pixels[4 * p])
        << "pixel " << p;
  }
}

// With media the camera's pass has scaled each emission by a sampled transmittance, so an
// emitter's radiance less its emission is not its reflected light: there emitters pass through
// untouched (bit for bit), noise and all.
TEST_F(DenoiseEmitterTest, EmittersPassThroughWhenTheLevelHasMedia) {
  ASSERT_EQ(foggy_lamp->volumes.size(), 1u);
  const lighting::GBufferTexels g = gbuffer(foggy_lamp);
  std::vector<std::uint8_t> emitters;
  const float c = 0.37f;
  ImageIntegrator* input = nullptr;
  auto h = harness(foggy_lamp, input);
  FrameSnapshot s = test::first_snapshot(foggy_lamp, kW, kH);
  for (std::uint32_t f = 0; f < 4; ++f) {
    if (f > 0) s = frozen(s);
    const ImageRGBA32F n = noisy(c, f);
    const ImageRGBA32F image = emission_plus(
        g, [&](std::size_t p, int k, bool) { return n.pixels[4 * p + k]; }, &emitters);
    input->set(image);
    const ImageRGBA32F out = h->render(s);
    std::size_t differing = 0;
    for (std::size_t p = 0; p < emitters.size(); ++p) {
      for (int k = 0; k < 3 && emitters[p]; ++k)
        differing += out.pixels[4 * p + k] != image.pixels[4 * p + k] ? 1 : 0;
    }
    ASSERT_GT(test::count(emitters), 100u);
    EXPECT_EQ(differing, 0u) << "frame " << f;
  }
}

}  // namespace
}  // namespace lantern::denoise_test
