// The denoise.* chain on images of known content: energy kept on a constant and on a noisy image
// of known mean, every pixel filtered at odd sizes, the device's workgroup shape, a shadow line
// kept dark, the sky filtered only with media, and no NaN/Inf from non-finite input.
#include "tests/denoise/denoise_gpu_fixture.h"

namespace lantern::denoise_test {
namespace {

// A constant image is a fixed point: every pixel, every frame (first, reprojected, filtered,
// stabilised).
TEST_F(DenoiseGpuTest, ConstantImageStaysConstant) {
  for (const char* stabilize : {"0", "0.7"}) {
    Run run = make_run({{"stabilize", stabilize}});
    FrameSnapshot s = test::first_snapshot(level, kW, kH);
    const float c = 0.37f;
    for (int f = 0; f < 5; ++f) {
      if (f > 0) s = frozen(s);
      const ImageRGBA32F out = render(run, constant(c), s);
      float worst = 0.0f;
      for (std::size_t i = 0; i < out.pixels.size(); ++i) {
        if (i % 4 == 3) continue;
        worst = std::max(worst, std::abs(out.pixels[i] - c) / c);
      }
      EXPECT_LT(worst, 1e-5f) << "stabilize " << stabilize << ", frame " << f
                              << ": a constant image must come out unchanged";
    }
  }
}

// The à-trous steps filter pixel pairs (shared/denoise.h): at sizes whose rows end in a partial
// pair block, with every tap spacing up to 16 pixels, a first frame of constant radiance comes
// out unchanged on every pixel (a pixel no thread wrote would hold a fresh buffer's content).
TEST_F(DenoiseGpuTest, EveryPixelIsFilteredAtOddSizes) {
  const float c = 0.37f;
  for (const auto& [w, h] : {std::pair{95u, 53u}, std::pair{37u, 21u}, std::pair{20u, 11u}}) {
    for (const char* atrous : {"1", "3", "5"}) {
      Run run = make_run({{"atrous", atrous}}, w, h);
      const ImageRGBA32F out = render(run, constant(c, w, h), test::first_snapshot(level, w, h));
      std::size_t wrong = 0;
      for (std::size_t i = 0; i < out.pixels.size(); ++i) {
        if (i % 4 != 3 && !(std::abs(out.pixels[i] - c) <= 1e-5f * c)) ++wrong;
      }
      EXPECT_EQ(wrong, 0u) << w << "x" << h << ", atrous " << atrous;
    }
  }
}

// The denoise.* passes take their workgroup shape from the device (lighting/frame/tile_order.h):
// rows of kPixelGroupCpuWidth threads on a CPU device such as this one (the sizes above then end
// in a partial row group: 95 = 64 + 31, 37, 20), kPixelGroupGpuSide squared on a GPU.
TEST_F(DenoiseGpuTest, PassesTakeTheDevicesWorkgroupShape) {
  const bool cpu = lighting::is_cpu_device(device.info());
  const std::array<std::uint32_t, 3> expected =
      cpu ? std::array<std::uint32_t, 3>{gpu::kPixelGroupCpuWidth, 1, 1}
          : std::array<std::uint32_t, 3>{gpu::kPixelGroupGpuSide, gpu::kPixelGroupGpuSide, 1};
  for (const char* stage : {"temporal", "variance", "atrous", "atrous_modulate", "modulate"}) {
    const lighting::DenoisePass pass(device, shaders, stage);
    EXPECT_EQ(pass.pipeline().local_size(), expected) << stage;
  }
}

// A noisy image of known mean keeps its mean (within 1% over the surfaces, 16 frames) while its
// pixel variance drops at least 10x (the denoiser's purpose).
TEST_F(DenoiseGpuTest, NoisyImageKeepsItsMean) {
  Run run = make_run();
  FrameSnapshot s = test::first_snapshot(level, kW, kH);
  const float c = 0.37f;
  lighting::GBufferTexels g;
  ImageRGBA32F out;
  for (std::uint32_t f = 0; f < 16; ++f) {
    if (f > 0) s = frozen(s);
    out = render(run, noisy(c, f), s, &g);
  }
  const std::vector<std::uint8_t> mask = surfaces(g);
  ASSERT_GT(test::count(mask), kW * kH / 2);
  const double mean = test::masked_mean(out, mask);
  double var_out = 0.0, var_in = 0.0;
  const ImageRGBA32F in = noisy(c, 15);
  for (std::size_t p = 0; p < mask.size(); ++p) {
    if (!mask[p]) continue;
    for (int k = 0; k < 3; ++k) {
      var_out += std::pow(out.pixels[4 * p + k] - c, 2.0);
      var_in += std::pow(in.pixels[4 * p + k] - c, 2.0);
    }
  }
  std::printf("[denoise noisy] mean %.5f (true %.5f), pixel variance in %.3g out %.3g (%.0fx)\n",
              mean, c, var_in, var_out, var_in / var_out);
  EXPECT_NEAR(mean / c, 1.0, 0.01);
  EXPECT_GT(var_in / var_out, 10.0);
}

// A line one pixel wide in shadow on a lit wall (a pole's shadow; static camera, c everywhere
// else) stays black once the history has settled, and the lit pixels beside it stay c. The first
// à-trous step compares 3x3 mean luminances; with equal weights they are the same (2c/3) on the
// line and beside it, and the stop let the lit pixels in (0.2 of 0.37 on the line); the tent,
// kDenoiseKernel, keeps each centre in front (c/2 against 3c/4). (The other leak seen there, a
// still point's motion of ~1e-4 px instead of 0, is GBufferMethodTest's exact-zero check.)
TEST_F(DenoiseGpuTest, ShadowLineOnALitWallStaysDark) {
  Run run = make_run();
  FrameSnapshot s = test::first_snapshot(level, kW, kH);
  const float c = 0.37f;
  const std::uint32_t line = kW / 5;  // left of the box: wall and floor
  ImageRGBA32F in = constant(c);
  for (std::uint32_t y = 0; y < kH; ++y) {
    for (int k = 0; k < 3; ++k) in.pixels[4 * (y * kW + line) + k] = 0.0f;
  }
  lighting::GBufferTexels g;
  ImageRGBA32F out;
  for (int f = 0; f < 16; ++f) {
    if (f > 0) s = frozen(s);
    out = render(run, in, s, &g);
  }
  // Where the line and its neighbours two pixels either side show one surface.
  std::size_t checked = 0;
  float darkest_lit = c, brightest_line = 0.0f;
  for (std::uint32_t y = 1; y + 1 < kH; ++y) {
    bool one_surface = true;
    for (std::uint32_t yy = y - 1; yy <= y + 1; ++yy) {
      for (std::uint32_t x = line - 2; x <= line + 2; ++x) {
        one_surface = one_surface && g.ids[yy * kW + x].x == g.ids[y * kW + line].x &&
                      g.ids[yy * kW + x].x != gpu::kNoInstance;
      }
    }
    if (!one_surface) continue;
    ++checked;
    brightest_line = std::max(brightest_line, out.pixels[4 * (y * kW + line)]);
    for (std::uint32_t x : {line - 1, line + 1}) {
      darkest_lit = std::min(darkest_lit, out.pixels[4 * (y * kW + x)]);
    }
  }
  std::printf(
      "[denoise shadow line] %zu rows: line at most %.3g, beside it at least %.5f (c %.2f)\n",
      checked, brightest_line, darkest_lit, c);
  ASSERT_GT(checked, kH / 4) << "the line should cross the wall and the floor";
  EXPECT_LE(brightest_line, 1e-3f * c) << "light leaked into the shadow line";
  EXPECT_NEAR(darkest_lit / c, 1.0, 0.01) << "the lit pixels beside the line lost light";
}

// With media (a level with a volume, here of zero density so the image reaching the denoiser is
// the test's own), the sky is filtered too: the fog in front of it is as noisy as any surface.
// Its pixels keep their mean (within 2%, 16 frames) while their variance drops at least 10x;
// without a volume they pass through untouched (bit for bit).
TEST_F(DenoiseGpuTest, SkyIsFilteredOnlyWhenTheLevelHasMedia) {
  std::string json = kScene;
  json.insert(json.rfind('}'), R"(, "volumes": [ { "name": "fog", "generate": { "type": "constant",
    "size": [2, 2, 2], "voxel_size": 0.5 }, "density_scale": 0.0 } ])");
  const auto foggy = test::level_from_json("denoise_corner_fog", json);
  ASSERT_EQ(foggy->volumes.size(), 1u);
  const float c = 0.37f;
  for (const bool media : {false, true}) {
    auto integrator = std::make_unique<ImageIntegrator>(device, kW, kH);
    ImageIntegrator* input = integrator.get();
    const std::shared_ptr<const Level> scene = media ? foggy : level;
    RenderHarness harness(device, shaders, scene, std::move(integrator), kW, kH);
    harness.renderer().set_output(lighting::FrameOutput::Denoised);
    harness.renderer().set_denoise_settings(lighting::make_denoise_settings("balanced", {}));
    FrameSnapshot s = test::first_snapshot(scene, kW, kH);
    lighting::GBufferTexels g;
    ImageRGBA32F out;
    for (std::uint32_t f = 0; f < 16; ++f) {
      if (f > 0) s = frozen(s);
      input->set(noisy(c, f));
      out = harness.render(s, &g);
    }
    std::vector<std::uint8_t> sky = surfaces(g);
    for (auto& m : sky) m = m ? 0 : 1;
    ASSERT_GT(test::count(sky), kW * kH / 20) << "the view shows sky";
    const ImageRGBA32F in = noisy(c, 15);
    double var_out = 0.0, var_in = 0.0;
    std::size_t differing = 0;
    for (std::size_t p = 0; p < sky.size(); ++p) {
      if (!sky[p]) continue;
      for (int k = 0; k < 3; ++k) {
        var_out += std::pow(out.pixels[4 * p + k] - c, 2.0);
        var_in += std::pow(in.pixels[4 * p + k] - c, 2.0);
        differing += out.pixels[4 * p + k] != in.pixels[4 * p + k] ? 1 : 0;
      }
    }
    const double mean = test::masked_mean(out, sky);
    std::printf("[denoise sky] media %d: sky mean %.5f (true %.5f), variance in %.3g out %.3g\n",
                int(media), mean, c, var_in, var_out);
    if (media) {
      EXPECT_NEAR(mean / c, 1.0, 0.02);
      EXPECT_GT(var_in / var_out, 10.0);
    } else {
      EXPECT_EQ(differing, 0u) << "without media the sky passes through";
    }
  }
}

// NaN and Inf in the input (a broken integrator) never reach the output, nor the history; nor
// does a finite value too large to square (1e30), among noise or alone among black pixels (the
// all-black history's unclamped moments), with the light the clamps take owed and repaid too
// (repay 1). The test sees the output; the moments' and the owed light's history stay finite by
// construction (kDenoiseMaxMomentLuminance).
TEST_F(DenoiseGpuTest, NonFiniteInputNeverReachesOutput) {
  const float bad[3] = {std::numeric_limits<float>::quiet_NaN(),
                        std::numeric_limits<float>::infinity(), 1.0e30f};
  const std::pair<const char*, const char*> settings[] = {
      {"0", "0"}, {"0.7", "0.25"}, {"0.7", "1"}};
  for (const auto& [stabilize, repay] : settings) {
    SCOPED_TRACE(std::string("stabilize ") + stabilize + ", repay " + repay);
    {
      Run run = make_run({{"stabilize", stabilize}, {"repay", repay}});
      FrameSnapshot s = test::first_snapshot(level, kW, kH);
      for (std::uint32_t f = 0; f < 6; ++f) {
        if (f > 0) s = frozen(s);
        ImageRGBA32F in = noisy(0.3f, f);
        for (std::size_t p = 0; p < in.pixels.size() / 4; p += 7) {
          in.pixels[4 * p + (p % 3)] = bad[p % 3];
        }
        const ImageRGBA32F out = render(run, in, s);
        EXPECT_TRUE(test::all_finite(out)) << "noisy, frame " << f;
        EXPECT_GT(runtime::mean_rgb(out), 0.1) << "frame " << f;
      }
    }
    // 6 black frames, then 1e30 in every 7th pixel: lone samples on all-black histories.
    Run run = make_run({{"stabilize", stabilize}, {"repay", repay}});
    std::vector<std::uint8_t> mask;
    FrameSnapshot s = black_frames(run, 6, mask);
    for (std::uint32_t f = 0; f < 4; ++f) {
      s = frozen(s);
      ImageRGBA32F in = constant(0.0f);
      for (std::size_t p = 0; p < in.pixels.size() / 4; p += 7) {
        for (int c = 0; c < 3; ++c) in.pixels[4 * p + c] = bad[2];
      }
      EXPECT_TRUE(test::all_finite(render(run, in, s))) << "black, lit frame " << f;
    }
  }
}

}  // namespace
}  // namespace lantern::denoise_test
