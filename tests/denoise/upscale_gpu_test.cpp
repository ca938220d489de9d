// upscale.temporal through the denoiser's fixture: scale 1 reproduces its input, a half internal
// size keeps a constant image and resamples a linear ramp exactly, the history stays on the scene
// for a still and a moving view, the jittered motion is the jitter step, and ReSTIR with jitter
// keeps the baseline's mean.
#include "tests/denoise/denoise_gpu_fixture.h"

namespace lantern::denoise_test {
namespace {

// upscale.temporal at scale 1 with no jitter reproduces its input exactly, frame after frame
// (history valid from the second frame on, but there is nothing to reconstruct).
TEST_F(DenoiseGpuTest, UpscalerAtScaleOneReproducesItsInput) {
  auto integrator = std::make_unique<ImageIntegrator>(device, kW, kH);
  ImageIntegrator* input = integrator.get();
  lighting::FrameRenderer renderer(device, shaders, level, std::move(integrator), kW, kH, 1);
  renderer.warm_up();
  runtime::HeadlessTarget target(device, {.width = kW, .height = kH});
  lighting::FrameSession session(device, target, renderer);
  lighting::Upscaler upscaler(device, shaders);
  upscaler.warm_up();
  lighting::FrameHooks hooks;
  hooks.hdr = [&](runtime::graph::RenderGraph& g, runtime::graph::BufferHandle hdr) {
    return upscaler.add_pass(g, renderer.last_inputs(), hdr, kW, kH);
  };
  FrameSnapshot s = test::first_snapshot(level, kW, kH);
  for (std::uint32_t f = 0; f < 3; ++f) {
    if (f > 0) s = frozen(s);
    const ImageRGBA32F in = noisy(0.4f, f);
    input->set(in);
    ASSERT_TRUE(session.render(s, hooks));
    const ImageRGBA32F out = target.read_output();
    std::size_t differ = 0;
    for (std::size_t i = 0; i < in.pixels.size(); ++i) differ += out.pixels[i] != in.pixels[i];
    EXPECT_EQ(differ, 0u) << "frame " << f;
  }
}

// Below the output size the frame renderer upscales; a constant image stays constant (bilinear
// resampling and the history clamp preserve it) and the output has the output size.
TEST_F(DenoiseGpuTest, HalfInternalSizeUpscalesAConstantImageUnchanged) {
  Run run = make_run();
  run.harness->renderer().set_internal_size(kW / 2, kH / 2);
  ASSERT_EQ(run.harness->renderer().width(), kW / 2);
  run.input->set(constant(0.25f));  // the first kW/2 x kH/2 pixels are read: all 0.25
  FrameSnapshot s = test::first_snapshot(level, kW, kH);
  for (int f = 0; f < 3; ++f) {
    if (f > 0) s = frozen(s);
    const ImageRGBA32F out = run.harness->render(s);
    ASSERT_EQ(out.width, kW);
    float worst = 0.0f;
    for (std::size_t i = 0; i < out.pixels.size(); ++i) {
      if (i % 4 != 3) worst = std::max(worst, std::abs(out.pixels[i] - 0.25f));
    }
    EXPECT_LT(worst, 1e-6f) << "frame " << f;
  }
  const auto& passes = run.harness->pass_ms();
  EXPECT_TRUE(std::any_of(passes.begin(), passes.end(),
                          [](const auto& p) { return p.first == "upscale.temporal"; }));
}

// upscale.temporal resamples this frame's jittered samples bilinearly: a linear ramp over the
// internal pixels comes out as the ramp at each output pixel's position in internal pixels,
// (o + 0.5) x in / out - 0.5 - jitter, where its bilinear footprint lies inside the image, and as
// the bilinear blend of the edge texels repeated outward at the borders (the first frame: no
// history to blend; raw output, so no filter touches the ramp). At half size, at a scale that is
// no simple fraction and one pixel short of the output (dynamic resolution's sizes).
TEST_F(DenoiseGpuTest, InternalSizesBelowTheOutputResampleALinearRampExactly) {
  const auto ramp = [](float x, float y) { return 0.1f + 0.01f * x + 0.02f * y; };
  // An odd output size too (95x53: the last 8x8 groups run past the last column and row).
  for (const auto& [w, h, internal] :
       {std::tuple{kW, kH, glm::uvec2(kW / 2, kH / 2)}, std::tuple{kW, kH, glm::uvec2(71, 40)},
        std::tuple{kW, kH, glm::uvec2(kW - 1, kH - 1)}, std::tuple{95u, 53u, glm::uvec2(47, 26)},
        std::tuple{95u, 53u, glm::uvec2(94, 52)}}) {
    const std::uint32_t kInW = internal.x, kInH = internal.y;
    Run run = make_run({}, w, h);
    run.harness->renderer().set_output(lighting::FrameOutput::Raw);
    run.harness->renderer().set_internal_size(kInW, kInH);
    const ImageRGBA32F in = internal_image(w, h, kInW, kInH, [&](std::uint32_t x, std::uint32_t y) {
      return ramp(static_cast<float>(x), static_cast<float>(y));
    });
    const ImageRGBA32F out = render(run, in, test::first_snapshot(level, w, h));
    ASSERT_EQ(out.width, w);
    const glm::vec2 jitter = run.harness->renderer().jitter();
    ASSERT_GT(glm::length(jitter), 0.0f) << "upscaling jitters the samples";
    const auto texel = [&](int x, int y) {  // clamped to the image, as the shader reads
      return ramp(static_cast<float>(std::clamp(x, 0, static_cast<int>(kInW) - 1)),
                  static_cast<float>(std::clamp(y, 0, static_cast<int>(kInH) - 1)));
    };
    const glm::vec2 scale(static_cast<float>(kInW) / w, static_cast<float>(kInH) / h);
    std::size_t inside = 0;
    float worst_inside = 0.0f, worst_border = 0.0f;
    for (std::uint32_t y = 0; y < h; ++y) {
      for (std::uint32_t x = 0; x < w; ++x) {
        const glm::vec2 u = (glm::vec2(x, y) + 0.5f) * scale - 0.5f - jitter;
        const glm::ivec2 b(std::floor(u.x), std::floor(u.y));
        const glm::vec2 f = u - glm::vec2(b);
        const float bilinear =
            (1 - f.y) * ((1 - f.x) * texel(b.x, b.y) + f.x * texel(b.x + 1, b.y)) +
            f.y * ((1 - f.x) * texel(b.x, b.y + 1) + f.x * texel(b.x + 1, b.y + 1));
        const bool interior =
            u.x >= 0.0f && u.y >= 0.0f && u.x <= kInW - 1.0f && u.y <= kInH - 1.0f;
        inside += interior;
        const float* p = &out.pixels[4 * (std::size_t{y} * w + x)];
        for (int c = 0; c < 3; ++c) {
          float& worst = interior ? worst_inside : worst_border;
          worst = std::max(worst, std::abs(p[c] - (interior ? ramp(u.x, u.y) : bilinear)));
        }
      }
    }
    std::printf("[upscale ramp] %ux%u from %ux%u: worst inside %.3g, at the borders %.3g\n", w, h,
                kInW, kInH, worst_inside, worst_border);
    EXPECT_GT(inside, std::size_t{w} * h * 3 / 4);
    EXPECT_LT(worst_inside, 1e-5f) << kInW << "x" << kInH << ": largest difference inside";
    EXPECT_LT(worst_border, 1e-5f) << kInW << "x" << kInH << ": largest difference at the borders";
  }
}

// A still view upscaled frame after frame: each frame's internal samples are a linear ramp taken
// at that frame's jittered positions (FrameRenderer::jitter_sequence), so each frame's bilinear
// resampling is the ramp at the output pixel, and the output history, which a still view must
// keep where it is, holds the same value: the output is the ramp at every interior pixel on every
// frame, history blended in from the second on. The motion vectors lead to last frame's jittered
// samples (the jitter step); reprojecting the unjittered output history along them moved it by
// twice that step each frame at half size (up to 0.017 off here: a blur of the whole image).
TEST_F(DenoiseGpuTest, StillViewKeepsTheUpscaledHistoryInPlace) {
  const auto ramp = [](float x, float y) { return 0.1f + 0.01f * x + 0.02f * y; };
  const std::uint32_t kInW = kW / 2, kInH = kH / 2;
  Run run = make_run();
  run.harness->renderer().set_output(lighting::FrameOutput::Raw);
  run.harness->renderer().set_internal_size(kInW, kInH);
  const glm::vec2 scale(static_cast<float>(kInW) / kW, static_cast<float>(kInH) / kH);
  FrameSnapshot s = test::first_snapshot(level, kW, kH);
  for (std::uint32_t f = 0; f < 10; ++f) {
    if (f > 0) s = frozen(s);
    const glm::vec2 jitter = lighting::FrameRenderer::jitter_sequence(f);
    const ImageRGBA32F in =
        internal_image(kW, kH, kInW, kInH, [&](std::uint32_t x, std::uint32_t y) {
          return ramp(static_cast<float>(x) + jitter.x, static_cast<float>(y) + jitter.y);
        });
    const ImageRGBA32F out = render(run, in, s);
    ASSERT_EQ(run.harness->renderer().jitter(), jitter) << "frame " << f;
    std::size_t inside = 0;
    float worst = 0.0f;
    for (std::uint32_t y = 0; y < kH; ++y) {
      for (std::uint32_t x = 0; x < kW; ++x) {
        // The output pixel in internal coordinates; its bilinear footprint stays inside the image
        // for every jitter (|jitter| < 0.5) away from the last internal pixel's half.
        const glm::vec2 u = (glm::vec2(x, y) + 0.5f) * scale - 0.5f;
        if (u.x < 0.5f || u.y < 0.5f || u.x > kInW - 1.5f || u.y > kInH - 1.5f) continue;
        ++inside;
        const float* p = &out.pixels[4 * (std::size_t{y} * kW + x)];
        for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(p[c] - ramp(u.x, u.y)));
      }
    }
    EXPECT_GT(inside, std::size_t{kW} * kH * 3 / 4);
    EXPECT_LT(worst, 1e-5f) << "frame " << f << ": largest difference from the ramp";
  }
}

// A moving view upscaled frame after frame: the camera looks straight at a wall and slides 0.37
// internal pixels sideways per frame, so every wall pixel moves by the same fraction of a pixel
// and each frame's output history is fetched between output pixels. The internal samples are a
// ramp in the wall's world x, taken at each frame's jittered positions; the upscaled image must
// be that ramp at every interior output pixel on every frame: the history follows the scene's
// motion (less the jitter step) and its Catmull-Rom fetch reproduces a linear function. With the
// motion's sign reversed the output is up to 0.013 off, with the jitter step left in 0.0042.
TEST_F(DenoiseGpuTest, MovingViewKeepsTheUpscaledHistoryOnTheScene) {
  const auto wall_level = test::level_from_json("denoise_wall", R"({
    "materials": { "grey": { "base_color": [0.5, 0.5, 0.5], "roughness": 0.8 } },
    "primitives": [ { "type": "plane", "name": "wall", "size": [60, 60], "material": "grey",
      "translation": [0, 0, -4], "rotation_deg": [90, 0, 0] } ],
    "lights": [ { "type": "point", "name": "lamp", "position": [0, 0, 1], "intensity": 1 } ],
    "camera": { "position": [0, 0, 0], "target": [0, 0, -1], "yfov_deg": 40 } })");
  constexpr float kDepth = 4.0f;  // the wall's distance along the view axis
  const std::uint32_t kInW = kW / 2, kInH = kH / 2;
  auto integrator = std::make_unique<ImageIntegrator>(device, kW, kH);
  ImageIntegrator* input = integrator.get();
  RenderHarness run(device, shaders, wall_level, std::move(integrator), kW, kH);
  run.renderer().set_output(lighting::FrameOutput::Raw);
  run.renderer().set_internal_size(kInW, kInH);
  FrameSnapshot s = test::first_snapshot(wall_level, kW, kH);
  ASSERT_LT(glm::length(
                glm::vec3(s.camera.orientation.x, s.camera.orientation.y, s.camera.orientation.z)),
            1e-6f)
      << "the camera looks down -z";
  // Internal pixels per world unit on the wall; the world x seen at internal column coordinate
  // sx (0 at the image's left edge) with the camera at cx.
  const float pixels_per_unit = 0.5f * static_cast<float>(kInH) / std::tan(0.5f * s.camera.yfov);
  const auto wall_x = [&](float sx, float cx) {
    return cx + (sx - 0.5f * static_cast<float>(kInW)) * kDepth / pixels_per_unit;
  };
  const auto ramp = [](float x) { return 1.0f + 0.1f * x; };
  const float step = 0.37f * kDepth / pixels_per_unit;  // world units per frame
  for (std::uint32_t f = 0; f < 10; ++f) {
    if (f > 0) {
      s = frozen(s);
      s.camera.position.x += step;
      s.camera.view = glm::inverse(glm::translate(glm::mat4(1.0f), s.camera.position) *
                                   glm::mat4_cast(s.camera.orientation));
    }
    const glm::vec2 jitter = lighting::FrameRenderer::jitter_sequence(f);
    input->set(internal_image(kW, kH, kInW, kInH, [&](std::uint32_t x, std::uint32_t) {
      return ramp(wall_x(static_cast<float>(x) + 0.5f + jitter.x, s.camera.position.x));
    }));
    const ImageRGBA32F out = run.render(s);
    ASSERT_EQ(run.renderer().jitter(), jitter) << "frame " << f;
    // Left out: 2 pixels at the top and bottom and 3 on the left (the history's 4x4 fetch reaches
    // past the image there), and 12 on the right, where the view brings in what last frame did
    // not show: its history is fetched from the border pixels, which pass the clamp near a ramp
    // and move inwards 0.74 output pixels a frame.
    float worst = 0.0f;
    std::size_t inside = 0;
    for (std::uint32_t y = 2; y + 2 < kH; ++y) {
      for (std::uint32_t x = 3; x + 12 < kW; ++x) {
        ++inside;
        const float sx = (static_cast<float>(x) + 0.5f) * static_cast<float>(kInW) / kW;
        const float want = ramp(wall_x(sx, s.camera.position.x));
        const float* p = &out.pixels[4 * (std::size_t{y} * kW + x)];
        for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(p[c] - want));
      }
    }
    EXPECT_GT(inside, std::size_t{kW} * kH * 3 / 4);
    EXPECT_LT(worst, 1e-4f) << "frame " << f << ": largest difference from the wall's ramp";
  }
}

// With the sample jitter on, a still scene's motion vectors are exactly the jitter step (this
// frame's offset minus last frame's: the previous frame's pixel whose sample was nearest), so
// ReSTIR's and the denoiser's reprojection stay consistent with it, and the points' own motion
// (zw, what upscale.temporal moves its unjittered history by) is exactly 0. Both G-buffer methods:
// the forward raster (96x54: few triangles per pixel) and cull + visibility + resolve (16x9: more
// than one triangle per 16 pixels, GBufferMethod::Auto's switch).
TEST_F(DenoiseGpuTest, JitteredMotionIsTheJitterStep) {
  for (const auto& [w, h] : {std::pair<std::uint32_t, std::uint32_t>{kW, kH}, {16u, 9u}}) {
    RenderHarness run(device, shaders, level, test::make_baseline(device, shaders), w, h);
    run.renderer().set_jitter(lighting::FrameRenderer::Jitter::On);
    FrameSnapshot s = test::first_snapshot(level, w, h);
    glm::vec2 previous(0.0f);
    for (int f = 0; f < 4; ++f) {
      if (f > 0) s = frozen(s);
      lighting::GBufferTexels g;
      (void)run.render(s, &g);
      const glm::vec2 jitter = run.renderer().jitter();
      EXPECT_GT(glm::length(jitter), 0.0f) << "frame " << f;
      EXPECT_LT(std::max(std::abs(jitter.x), std::abs(jitter.y)), 0.5f);
      if (f > 0) {
        const glm::vec2 step = jitter - previous;
        std::size_t surfaces = 0, exact = 0, still = 0;
        for (std::size_t p = 0; p < g.ids.size(); ++p) {
          if (g.ids[p].x == gpu::kNoInstance) continue;
          ++surfaces;
          exact += glm::length(glm::vec2(g.motion[p]) - step) < 1e-3f;
          still += g.motion[p].z == 0.0f && g.motion[p].w == 0.0f;
        }
        EXPECT_GT(surfaces, std::size_t{w} * h / 2);
        EXPECT_EQ(exact, surfaces)
            << w << "x" << h << " frame " << f << ": motion must be the jitter step";
        EXPECT_EQ(still, surfaces)
            << w << "x" << h << " frame " << f << ": the points' own motion (zw) must be exactly 0";
      }
      previous = jitter;
    }
  }
}

// ReSTIR stays unbiased with the jitter on: on a still cornell_lights, the mean of 32 jittered
// ReSTIR frames matches the mean of 64 jittered baseline frames (both integrate the pixel
// footprint) within 3%.
TEST_F(DenoiseGpuTest, JitteredRestirMatchesJitteredBaseline) {
  auto cornell = std::make_shared<const Level>(load_level_argument("cornell_lights"));
  const FrameSnapshot first = test::first_snapshot(cornell, kW, kH);
  auto mean_of = [&](std::unique_ptr<lighting::Integrator> integrator, int frames) {
    RenderHarness h(device, shaders, cornell, std::move(integrator), kW, kH);
    h.renderer().set_jitter(lighting::FrameRenderer::Jitter::On);
    runtime::ImageAccumulator acc;
    FrameSnapshot s = first;
    for (int f = 0; f < frames; ++f) {
      if (f > 0) s = frozen(s);
      acc.add(h.render(s));
    }
    return runtime::mean_rgb(acc.mean());
  };
  const double restir = mean_of(test::make_restir(device, shaders, {}), 32);
  const double baseline = mean_of(test::make_baseline(device, shaders), 64);
  std::printf("[jitter bias] ReSTIR %.5f, baseline %.5f (ratio %.4f)\n", restir, baseline,
              restir / baseline);
  EXPECT_NEAR(restir / baseline, 1.0, 0.03);
}

}  // namespace
}  // namespace lantern::denoise_test
