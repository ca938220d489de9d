// The denoiser's history: rejected across a camera cut, a disocclusion and a mostly hidden
// footprint (exact images), recovered within four frames; the clamps (a light after darkness, a
// lone sample without history, a dimmed light, a lit pixel among dark ones) and what they took
// given back (repay), a dark pixel among lit ones in a short history and one whose samples agree
// by chance among noisy ones, the stabilisation, and each frame weighed by the integrator's
// confidence.
#include "tests/denoise/denoise_gpu_fixture.h"

namespace lantern::denoise_test {

void DenoiseGpuTest::expect_cut_rejects_history(
    const std::vector<std::pair<std::string, std::string>>& settings) {
  const FrameSnapshot first = test::first_snapshot(level, kW, kH);
  Run run = make_run(settings);
  FrameSnapshot s = first;
  for (int f = 0; f < 4; ++f) {
    if (f > 0) s = frozen(s);
    (void)render(run, noisy(0.2f, f), s);
  }
  FrameSnapshot cut = frozen(s);
  cut.camera_cut = true;
  const ImageRGBA32F after_cut = render(run, noisy(0.6f, 9), cut);
  EXPECT_FALSE(run.harness->renderer().history_valid());

  Run fresh = make_run(settings);
  const ImageRGBA32F expected = render(fresh, noisy(0.6f, 9), cut);
  ASSERT_EQ(after_cut.pixels.size(), expected.pixels.size());
  std::size_t differ = 0;
  for (std::size_t i = 0; i < expected.pixels.size(); ++i)
    differ += after_cut.pixels[i] != expected.pixels[i];
  EXPECT_EQ(differ, 0u) << "the frame after a cut must not see any history";

  // Control: the same frame without the cut blends history (darker: 0.2 before, 0.6 now).
  Run kept = make_run(settings);
  s = first;
  for (int f = 0; f < 4; ++f) {
    if (f > 0) s = frozen(s);
    (void)render(kept, noisy(0.2f, f), s);
  }
  const ImageRGBA32F blended = render(kept, noisy(0.6f, 9), frozen(s));
  EXPECT_TRUE(kept.harness->renderer().history_valid());
  EXPECT_LT(runtime::mean_rgb(blended), 0.9 * runtime::mean_rgb(expected));
}

namespace {

// A camera cut drops all history: the frame after the cut is exactly (bit for bit) the first
// frame of a fresh renderer fed the same image; without the cut it is not.
TEST_F(DenoiseGpuTest, CameraCutRejectsHistory) {
  for (const char* stabilize : {"0", "0.7"}) {
    SCOPED_TRACE(std::string("stabilize ") + stabilize);
    expect_cut_rejects_history({{"stabilize", stabilize}});
  }
}

// The box moves away at frame 4 (static camera): the wall it uncovers has no history (its output
// is exactly this frame's input), while the wall that stayed visible blends its history with
// alpha = max(1 / 5 frames, color_alpha) = 0.2. Temporal only (atrous 0) so each pixel is exact.
TEST_F(DenoiseGpuTest, DisocclusionRejectsHistory) {
  const std::size_t box = instance_index(*level, "box");
  Run run = make_run({{"atrous", "0"}, {"firefly", "0"}});
  FrameSnapshot s = test::first_snapshot(level, kW, kH);
  const float before = 0.2f, now = 0.6f;
  lighting::GBufferTexels previous, current;
  for (int f = 0; f < 4; ++f) {
    if (f > 0) s = frozen(s);
    (void)render(run, constant(before), s, &previous);
  }
  s = frozen(s);
  s.instances[box].object_to_world = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, 50.0f)) *
                                     s.instances[box].object_to_world;
  const ImageRGBA32F out = render(run, constant(now), s, &current);
  ASSERT_TRUE(run.harness->renderer().history_valid());

  const float blended = 0.8f * before + 0.2f * now;
  std::size_t uncovered = 0, uncovered_exact = 0, stayed = 0, stayed_exact = 0;
  for (std::size_t p = 0; p < current.ids.size(); ++p) {
    const std::uint32_t was = previous.ids[p].x, is = current.ids[p].x;
    if (is == gpu::kNoInstance || is == box) continue;
    const float r = out.pixels[4 * p];
    if (was == box) {
      ++uncovered;
      uncovered_exact += std::abs(r - now) <= 1e-5f * now;
    } else if (was == is) {
      ++stayed;
      stayed_exact += std::abs(r - blended) <= 1e-5f * blended;
    }
  }
  std::printf(
      "[denoise disocclusion] %zu uncovered pixels (%zu = input), %zu stayed (%zu = "
      "blend)\n",
      uncovered, uncovered_exact, stayed, stayed_exact);
  ASSERT_GT(uncovered, 100u) << "the box must uncover part of the wall";
  ASSERT_GT(stayed, 1000u);
  EXPECT_EQ(uncovered_exact, uncovered) << "uncovered pixels must not reuse the box's history";
  EXPECT_EQ(stayed_exact, stayed) << "pixels whose surface stayed must blend their history";
}

// The box moves sideways by 0.2-0.4 of a pixel (static camera): along its leading edge a box
// pixel's bilinear footprint in the last frame is mostly wall. Where less than half of it
// (kDenoiseMinHistoryFootprint) was the box even by the loosest test (same instance; the real one
// also asks for the same plane and normal), the pixel has no history: it comes out as exactly
// this frame's input, where renormalising the few box taps used to give it their history. Pixels
// whose footprint was all box still blend theirs. Temporal only, as above.
TEST_F(DenoiseGpuTest, MostlyHiddenFootprintHasNoHistory) {
  const std::size_t box = instance_index(*level, "box");
  const float before = 0.2f, now = 0.6f;
  std::size_t partial = 0, partial_exact = 0, whole = 0, whole_blended = 0;
  float smallest_motion = 1e9f, largest_motion = 0.0f;
  // A step of ~0.3 px from four starting places a quarter pixel apart: wherever the leading edge
  // crosses a pixel centre, that pixel was wall last frame, and its footprint there holds the
  // wall pixel at 1 - motion and the box pixel behind it at the motion.
  const auto moved = [&](FrameSnapshot s, float dx) {
    s.instances[box].object_to_world = glm::translate(glm::mat4(1.0f), glm::vec3(dx, 0.0f, 0.0f)) *
                                       s.instances[box].object_to_world;
    return s;
  };
  for (const float start : {0.0f, 0.019f, 0.038f, 0.057f}) {
    Run run = make_run({{"atrous", "0"}, {"firefly", "0"}});
    FrameSnapshot s = moved(test::first_snapshot(level, kW, kH), start);
    lighting::GBufferTexels previous, current;
    for (int f = 0; f < 4; ++f) {
      if (f > 0) s = frozen(s);
      (void)render(run, constant(before), s, &previous);
    }
    s = moved(frozen(s), 0.022f);
    const ImageRGBA32F out = render(run, constant(now), s, &current);
    ASSERT_TRUE(run.harness->renderer().history_valid());
    for (std::uint32_t y = 0; y < kH; ++y) {
      for (std::uint32_t x = 0; x < kW; ++x) {
        const std::size_t p = std::size_t{y} * kW + x;
        if (current.ids[p].x != box) continue;
        const glm::vec2 motion(current.motion[p]);
        smallest_motion = std::min(smallest_motion, glm::length(motion));
        largest_motion = std::max(largest_motion, glm::length(motion));
        // The shader's footprint: previous pixel centre minus 0.5, bilinear over 2x2.
        const glm::vec2 q = glm::vec2(x, y) + motion;
        const glm::ivec2 base(std::floor(q.x), std::floor(q.y));
        const glm::vec2 f = q - glm::vec2(base);
        float box_share = 0.0f, inside = 0.0f;
        for (int t = 0; t < 4; ++t) {
          const glm::ivec2 tap = base + glm::ivec2(t & 1, t >> 1);
          const float w = ((t & 1) ? f.x : 1.0f - f.x) * ((t >> 1) ? f.y : 1.0f - f.y);
          if (w <= 0.0f || tap.x < 0 || tap.y < 0 || tap.x >= int(kW) || tap.y >= int(kH)) continue;
          inside += w;
          if (previous.ids[std::size_t(tap.y) * kW + std::size_t(tap.x)].x == box) box_share += w;
        }
        const float r = out.pixels[4 * p];
        if (box_share > 0.05f && box_share < 0.4f) {
          ++partial;
          partial_exact += std::abs(r - now) <= 1e-5f * now;
        } else if (box_share > 0.999f && inside > 0.999f) {
          ++whole;
          whole_blended += r < 0.99f * now;
        }
      }
    }
  }
  std::printf(
      "[denoise partial footprint] box motion %.2f..%.2f px; %zu box pixels less than 0.4 "
      "box last frame (%zu = input), %zu all box (%zu blended)\n",
      smallest_motion, largest_motion, partial, partial_exact, whole, whole_blended);
  ASSERT_GT(smallest_motion, 0.1f) << "the box barely moved";
  ASSERT_LT(largest_motion, 0.45f) << "the box should move less than half a pixel";
  ASSERT_GT(partial, 5u) << "no box pixel had a footprint mostly on the wall";
  ASSERT_GT(whole, 500u);
  EXPECT_EQ(partial_exact, partial) << "a mostly hidden footprint must not give history";
  EXPECT_GT(whole_blended, whole * 9 / 10) << "a footprint on the box must keep its history";
}

// The box moves away after 8 frames of a noisy image of known mean (static camera): the wall it
// uncovers starts without history, and within 4 frames it must be as clean as the wall that never
// lost its history would be after as many frames (RMS error within 2x of the stayed wall's at
// frame 4, whose history is 12 frames: so within 2x of a longer-settled estimate) and keep the
// mean (within 3%; 4 frames of spatially boosted filtering average few samples).
TEST_F(DenoiseGpuTest, DisocclusionRecoversWithinFourFrames) {
  const std::size_t box = instance_index(*level, "box");
  Run run = make_run();
  FrameSnapshot s = test::first_snapshot(level, kW, kH);
  const float c = 0.37f;
  lighting::GBufferTexels before, after;
  std::uint32_t f = 0;
  for (; f < 8; ++f) {
    if (f > 0) s = frozen(s);
    (void)render(run, noisy(c, f), s, &before);
  }
  s = frozen(s);
  s.instances[box].object_to_world = glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, 50.0f)) *
                                     s.instances[box].object_to_world;
  for (int k = 1; k <= 4; ++k, ++f) {
    if (k > 1) s = frozen(s);
    const ImageRGBA32F out = render(run, noisy(c, f), s, &after);
    double uncovered_se = 0.0, stayed_se = 0.0, uncovered_sum = 0.0;
    std::size_t uncovered = 0, stayed = 0;
    for (std::size_t p = 0; p < after.ids.size(); ++p) {
      const std::uint32_t was = before.ids[p].x, is = after.ids[p].x;
      if (is == gpu::kNoInstance || is == box) continue;
      double se = 0.0;
      for (int ch = 0; ch < 3; ++ch) se += std::pow(out.pixels[4 * p + ch] - c, 2.0) / 3.0;
      if (was == box) {
        uncovered_se += se;
        uncovered_sum += (out.pixels[4 * p] + out.pixels[4 * p + 1] + out.pixels[4 * p + 2]) / 3.0;
        ++uncovered;
      } else if (was == is) {
        stayed_se += se;
        ++stayed;
      }
    }
    ASSERT_GT(uncovered, 100u);
    ASSERT_GT(stayed, 1000u);
    const double uncovered_rms = std::sqrt(uncovered_se / uncovered) / c;
    const double stayed_rms = std::sqrt(stayed_se / stayed) / c;
    const double mean = uncovered_sum / uncovered / c;
    std::printf(
        "[denoise disocclusion recovery] frame %d after: uncovered RMS %.4f mean %.4f, "
        "stayed RMS %.4f (%.2fx)\n",
        k, uncovered_rms, mean, stayed_rms, uncovered_rms / stayed_rms);
    if (k == 4) {
      EXPECT_LT(uncovered_rms, 2.0 * stayed_rms) << "the uncovered wall has not recovered";
      EXPECT_NEAR(mean, 1.0, 0.03);
    }
  }
}

// A light switched on after frames of darkness shows at once (static camera, firefly clamp on):
// a history that has seen only black is no evidence against a new sample, so the first lit frame
// blends it in (alpha 1/7 after 6 dark frames: c/7 on every surface pixel) and 30 frames later
// the image is within 5% of c (0.9^23 of the dark history left).
TEST_F(DenoiseGpuTest, LightAfterDarknessIsNotHeldBlack) {
  Run run = make_run();
  std::vector<std::uint8_t> mask;
  FrameSnapshot s = black_frames(run, 6, mask);
  ASSERT_GT(test::count(mask), kW * kH / 2);
  const float c = 0.4f;
  s = frozen(s);
  ImageRGBA32F out = render(run, constant(c), s);
  const Range r = masked_range(out, mask);
  std::printf("[denoise light on] first lit frame: surfaces %.5f..%.5f (c/7 = %.5f)\n", r.lo, r.hi,
              c / 7.0f);
  EXPECT_NEAR(r.lo, c / 7.0f, 1e-4f) << "a pixel was held black by its dark history";
  EXPECT_NEAR(r.hi, c / 7.0f, 1e-4f);
  for (int f = 0; f < 30; ++f) {
    s = frozen(s);
    out = render(run, constant(c), s);
  }
  EXPECT_NEAR(test::masked_mean(out, mask) / c, 1.0, 0.05);
}

// A lone heavy sample on a pixel with no history to judge it (the first frame, temporal only) is
// clamped to neighbour_clamp x its brightest neighbour: one surface pixel at 100 c among pixels
// of c comes out at exactly 2 c (the balanced preset's 2), every other pixel at c; with the
// clamp off it stays 100 c. Once the history is long (6 frames of c), the history's own clamp
// (mean + firefly sigma = c) judges the same spike instead.
TEST_F(DenoiseGpuTest, LoneSampleWithoutHistoryIsClampedToItsNeighbours) {
  const float c = 0.3f;
  std::vector<std::uint8_t> mask;
  std::size_t spike = 0;
  const ImageRGBA32F input = lone_spike(c, 100.0f, spike, mask);
  ASSERT_NE(spike, 0u);
  struct Case {
    const char* what;
    const char* clamp;
    int history_frames;
    float expected;
  };
  const Case cases[] = {{"first frame, clamp 2", "2", 0, 2.0f * c},
                        {"first frame, clamp off", "0", 0, 100.0f * c},
                        {"after 6 frames of c", "2", 6, c}};
  for (const Case& k : cases) {
    Run run = make_run({{"atrous", "0"}, {"neighbour_clamp", k.clamp}});
    FrameSnapshot s = test::first_snapshot(level, kW, kH);
    for (int f = 0; f < k.history_frames; ++f) {
      (void)render(run, constant(c), s);
      s = frozen(s);
    }
    const ImageRGBA32F out = render(run, input, s);
    // Away from the spike every surface pixel is c (the blend of c with a history of c).
    std::vector<std::uint8_t> others = mask;
    others[spike] = 0;
    const Range r = masked_range(out, others);
    std::printf("[denoise neighbour clamp] %s: spike %.5f (expected %.5f), others %.5f..%.5f\n",
                k.what, out.pixels[4 * spike], k.expected, r.lo, r.hi);
    EXPECT_NEAR(out.pixels[4 * spike], k.expected, 1e-4f * k.expected) << k.what;
    EXPECT_NEAR(r.lo, c, 1e-5f) << k.what;
    EXPECT_NEAR(r.hi, c, 1e-5f) << k.what;
  }
}

// The neighbour clamp judges a sample by the neighbours on the pixel's own surface (first frame,
// temporal only). The box stands at c / 10 before a wall and floor at c; a pixel of its left
// silhouette (the wall beside it) gets 1.5 c. Its neighbours on the box's face set the limit,
// 2 x c / 10; all 8 would let the sample through, since the wall's c admits it (what the clamp did
// before: a pole one pixel wide kept the heavy samples of the lit wall beside it); with the clamp
// off it keeps 1.5 c. The wall keeps c. (A pixel none of whose neighbours is on its surface is
// judged by all 8, as before; this scene has no such pixel, so that branch is not tested here.)
TEST_F(DenoiseGpuTest, LoneSampleIsJudgedByTheNeighboursOnItsOwnSurface) {
  const float c = 0.3f;
  const std::uint32_t box = static_cast<std::uint32_t>(instance_index(*level, "box"));
  const lighting::GBufferTexels g = first_frame_gbuffer();
  auto id = [&](std::uint32_t x, std::uint32_t y) { return g.ids[std::size_t{y} * kW + x].x; };
  // The box pixels whose left neighbour is a surface other than the box and whose other 7
  // neighbours are the box: its left silhouette; the middle one of them is the spike.
  std::vector<std::size_t> silhouette;
  for (std::uint32_t y = 1; y + 1 < kH; ++y) {
    for (std::uint32_t x = 1; x + 1 < kW; ++x) {
      bool box_right = true;
      for (int dy = -1; dy <= 1; ++dy) {
        box_right = box_right && id(x, y + dy) == box && id(x + 1, y + dy) == box;
      }
      const std::uint32_t left = id(x - 1, y);
      if (box_right && left != box && left != gpu::kNoInstance) {
        silhouette.push_back(std::size_t{y} * kW + x);
      }
    }
  }
  ASSERT_GE(silhouette.size(), 5u) << "the box must show a left silhouette against the wall";
  const std::size_t spike = silhouette[silhouette.size() / 2];
  const std::size_t wall = spike - 1;
  ImageRGBA32F input = constant(c);
  for (std::size_t p = 0; p < g.ids.size(); ++p) {
    for (int k = 0; k < 3; ++k) {
      if (g.ids[p].x == box) input.pixels[4 * p + k] = 0.1f * c;
      if (p == spike) input.pixels[4 * p + k] = 1.5f * c;
    }
  }
  struct Case {
    const char* clamp;
    float expected;
  };
  for (const Case& k : {Case{"2", 0.2f * c}, Case{"0", 1.5f * c}}) {
    Run run = make_run({{"atrous", "0"}, {"neighbour_clamp", k.clamp}});
    const ImageRGBA32F out = render(run, input, test::first_snapshot(level, kW, kH));
    std::printf("[denoise own surface] clamp %s: silhouette pixel %.5f (expected %.5f), wall %.5f\n",
                k.clamp, out.pixels[4 * spike], k.expected, out.pixels[4 * wall]);
    EXPECT_NEAR(out.pixels[4 * spike], k.expected, 1e-4f * k.expected) << "clamp " << k.clamp;
    EXPECT_NEAR(out.pixels[4 * wall], c, 1e-5f) << "clamp " << k.clamp;
  }
}

// Two heavy samples side by side without history (the first frame, temporal only), on the wall:
// each is judged by the second brightest of its neighbours on its surface, so neither vouches for
// the other and both come out at exactly 2 c (neighbour_clamp 2 x the wall's c); with the clamp
// off both keep 100 c. By the brightest neighbour (the clamp before) each admitted the other and
// both kept 100 c: ReSTIR's heavy samples come in such clusters where spatial reuse spread one
// over a few pixels. The rest of the wall keeps c.
TEST_F(DenoiseGpuTest, HeavySamplesSideBySideDoNotVouchForEachOther) {
  const float c = 0.3f;
  lighting::GBufferTexels g;
  const std::size_t first = wall_block(1, 2, 1, 1, g);  // the pair's 4x3 block is wall
  ASSERT_NE(first, 0u) << "the wall must show a 4x3 block";
  const std::size_t pair[2] = {first, first + 1};
  ImageRGBA32F input = constant(c);
  std::vector<std::uint8_t> others(g.ids.size(), 0);
  for (std::size_t p = 0; p < g.ids.size(); ++p) others[p] = g.ids[p].x == g.ids[first].x;
  for (const std::size_t p : pair) {
    for (int k = 0; k < 3; ++k) input.pixels[4 * p + k] = 100.0f * c;
    others[p] = 0;
  }
  struct Case {
    const char* clamp;
    float expected;
  };
  for (const Case& k : {Case{"2", 2.0f * c}, Case{"0", 100.0f * c}}) {
    Run run = make_run({{"atrous", "0"}, {"neighbour_clamp", k.clamp}});
    const ImageRGBA32F out = render(run, input, test::first_snapshot(level, kW, kH));
    const Range r = masked_range(out, others);
    std::printf("[denoise vouching] clamp %s: pair %.5f %.5f (expected %.5f), wall %.5f..%.5f\n",
                k.clamp, out.pixels[4 * pair[0]], out.pixels[4 * pair[1]], k.expected, r.lo, r.hi);
    for (const std::size_t p : pair) {
      EXPECT_NEAR(out.pixels[4 * p], k.expected, 1e-4f * k.expected) << "clamp " << k.clamp;
    }
    EXPECT_NEAR(r.lo, c, 1e-5f) << "clamp " << k.clamp;
    EXPECT_NEAR(r.hi, c, 1e-5f) << "clamp " << k.clamp;
  }
}

// A dark pixel without history (the first frame: as just disoccluded) on a lit wall of c, with one
// à-trous step at a tight luminance stop (phi_luminance 0.1): denoise.variance estimates its
// variance from the 5x5 wall around it, and the step weighs the lit neighbours by that spread
// as it is. SVGF's boost (x4 at one frame) doubled the stop's scale, and the dark pixel took in
// 0.083 c of its neighbours' light; unboosted it reads 0.0035 c (asked: under 0.02 c), the wall
// out of its reach c.
TEST_F(DenoiseGpuTest, DarkPixelWithoutHistoryIsJudgedByItsNeighboursSpread) {
  const float c = 0.3f;
  lighting::GBufferTexels g;
  const std::size_t dark = wall_block(4, 4, 4, 4, g);
  ASSERT_NE(dark, 0u) << "the wall must show a 9x9 block";
  ImageRGBA32F input = constant(c);
  for (int k = 0; k < 3; ++k) input.pixels[4 * dark + k] = 0.0f;
  Run run = make_run({{"atrous", "1"}, {"phi_luminance", "0.1"}});
  const ImageRGBA32F out = render(run, input, test::first_snapshot(level, kW, kH));
  const float far = out.pixels[4 * (dark + 3 * kW)];  // three rows below: no dark pixel in reach
  std::printf("[denoise unboosted] dark pixel %.5f (c %.5f), wall three rows below %.5f\n",
              out.pixels[4 * dark], c, far);
  EXPECT_LT(out.pixels[4 * dark], 0.02f * c) << "the dark pixel took in its neighbours' light";
  EXPECT_NEAR(far, c, 1e-5f);
}

// What a clamp takes is repaid with denoise.repay (static camera, temporal only, every frame
// weighed alike: color_alpha 0.01, max_history 64, antilag off). Frame 0 holds a lone 100c spike
// on a surface of c, which the neighbour clamp cuts to 2c (98c taken), then 12 frames of c; the
// spike pixel shows the mean of the 13 samples it kept. Off: (2c + 12c) / 13. Repay 1: each frame
// gives back as much as the limit leaves room for (2c: the neighbour clamp while the history is
// short, then the history's mean + 4 sigma of samples that are all 2c), so every sample is 2c and
// none above it. Repay 0.005: frame k gives back 0.005 x 98c x 0.995^(k-1) (below the room
// left), 98c (1 - 0.995^12) in all. The other pixels stay c, and a camera cut drops what is owed
// with the history (the spike pixel is c again).
TEST_F(DenoiseGpuTest, ClampedLightIsRepaidUpToTheClampsLimit) {
  const float c = 0.3f;
  std::vector<std::uint8_t> mask;
  std::size_t spike = 0;
  const ImageRGBA32F input = lone_spike(c, 100.0f, spike, mask);
  ASSERT_NE(spike, 0u);
  constexpr int kFrames = 13;
  struct Case {
    const char* repay;
    float expected;
  };
  const Case cases[] = {
      {"0", 14.0f * c / kFrames},
      {"1", 2.0f * c},
      {"0.005", (14.0f * c + 98.0f * c * (1.0f - std::pow(0.995f, kFrames - 1.0f))) / kFrames}};
  std::vector<std::uint8_t> others = mask;
  others[spike] = 0;
  for (const Case& k : cases) {
    Run run = make_run({{"atrous", "0"},
                        {"neighbour_clamp", "2"},
                        {"color_alpha", "0.01"},
                        {"max_history", "64"},
                        {"antilag", "0"},
                        {"repay", k.repay}});
    FrameSnapshot s = test::first_snapshot(level, kW, kH);
    ImageRGBA32F out = render(run, input, s);
    for (int f = 1; f < kFrames; ++f) {
      s = frozen(s);
      out = render(run, constant(c), s);
    }
    const Range r = masked_range(out, others);
    std::printf("[denoise repay] repay %s: spike %.5f (expected %.5f), others %.5f..%.5f\n",
                k.repay, out.pixels[4 * spike], k.expected, r.lo, r.hi);
    EXPECT_NEAR(out.pixels[4 * spike], k.expected, 1e-3f * k.expected) << "repay " << k.repay;
    EXPECT_NEAR(r.lo, c, 1e-5f) << "repay " << k.repay;
    EXPECT_NEAR(r.hi, c, 1e-5f) << "repay " << k.repay;
    s = frozen(s);
    s.camera_cut = true;
    out = render(run, constant(c), s);
    EXPECT_NEAR(out.pixels[4 * spike], c, 1e-5f) << "repay " << k.repay << ", after a cut";
  }
}

// A light dimmed under a long history is followed within the short one (static camera, temporal
// only, a long colour history: color_alpha 0.02, max_history 64): 40 frames of c, then c/4.
// Without antilag the colour history fades by 1/41 a frame (0.86 c after 8 dimmed frames, still
// 2.3 x c/4 after 38); with it the history is held within one standard error of the luminance
// moments' mean (a ~9-frame window: at most 0.51 c after 8 frames by the closed form, 0.504 c
// measured), never below c/4, and within 5% of c/4 after 38 frames. A constant image is not
// touched (ConstantImageStaysConstant runs with the preset's antilag).
TEST_F(DenoiseGpuTest, DimmedLightIsFollowedWithinTheShortHistory) {
  const float c = 0.4f;
  float after8[2] = {0.0f, 0.0f};
  for (int antilag = 0; antilag < 2; ++antilag) {
    Run run = make_run({{"atrous", "0"},
                        {"color_alpha", "0.02"},
                        {"max_history", "64"},
                        {"antilag", antilag == 0 ? "0" : "1"}});
    std::vector<std::uint8_t> mask;
    FrameSnapshot s = black_frames(run, 1, mask);
    for (int f = 0; f < 40; ++f) {
      s = frozen(s);
      (void)render(run, constant(c), s);
    }
    ImageRGBA32F out;
    for (int f = 0; f < 38; ++f) {
      s = frozen(s);
      out = render(run, constant(c / 4.0f), s);
      const Range r = masked_range(out, mask);
      EXPECT_GE(r.lo, c / 4.0f - 1e-5f) << "antilag " << antilag << ", dimmed frame " << f + 1;
      if (f == 7) after8[antilag] = r.hi;
    }
    const Range r = masked_range(out, mask);
    std::printf(
        "[denoise antilag %d] 8 dimmed frames: surfaces up to %.5f; 38: %.5f..%.5f (c/4 = "
        "%.5f)\n",
        antilag, after8[antilag], r.lo, r.hi, c / 4.0f);
    if (antilag == 1) {
      EXPECT_NEAR(r.hi / (c / 4.0f), 1.0, 0.05);
    }
  }
  EXPECT_GT(after8[0], 0.8f * c) << "without antilag the long history should still lag";
  EXPECT_LT(after8[1], 0.52f * c) << "antilag did not hold the history to the short window";
}

// Stabilisation (denoise.stabilize) on a still view of noise with a known mean: the frame-to-frame
// change of the output (what trade's flicker measures) drops, the mean stays, and when the light
// drops to a quarter the output follows: the band (stabilize_band standard deviations of the
// filtered frame) lets the blend lag by no more than the filter's own noise. A history younger
// than kDenoiseShortHistory frames is not stabilised at all: the first frames are exactly the
// unstabilised ones.
TEST_F(DenoiseGpuTest, StabilisationSteadiesAStillViewAndFollowsALightThatChanges) {
  const float c = 0.37f;
  std::vector<ImageRGBA32F> young[2];
  double change[2] = {0.0, 0.0};
  double mean[2] = {0.0, 0.0};
  double dimmed[2] = {0.0, 0.0};
  for (int k = 0; k < 2; ++k) {
    Run run = make_run({{"stabilize", k == 0 ? "0" : "0.7"}});
    FrameSnapshot s = test::first_snapshot(level, kW, kH);
    lighting::GBufferTexels g;
    ImageRGBA32F previous;
    ImageRGBA32F out;
    for (std::uint32_t f = 0; f < 20; ++f) {
      if (f > 0) s = frozen(s);
      previous = std::move(out);
      out = render(run, noisy(c, f), s, &g);
      if (f + 1 < gpu::kDenoiseShortHistory) young[k].push_back(out);
      if (f < 16) continue;  // the last 4 frame pairs
      const std::vector<std::uint8_t> mask = surfaces(g);
      for (std::size_t p = 0; p < mask.size(); ++p) {
        if (!mask[p]) continue;
        for (int ch = 0; ch < 3; ++ch)
          change[k] += std::pow(out.pixels[4 * p + ch] - previous.pixels[4 * p + ch], 2.0);
      }
    }
    const std::vector<std::uint8_t> mask = surfaces(g);
    ASSERT_GT(test::count(mask), kW * kH / 2);
    mean[k] = test::masked_mean(out, mask);
    for (std::uint32_t f = 0; f < 8; ++f) {
      s = frozen(s);
      out = render(run, noisy(c / 4.0f, 100 + f), s);
    }
    dimmed[k] = test::masked_mean(out, mask);
  }
  std::printf(
      "[denoise stabilize] frame-to-frame change %.4g -> %.4g (%.2fx); mean %.5f / %.5f (c "
      "%.5f); 8 frames after dimming to c/4 %.5f / %.5f (c/4 %.5f)\n",
      change[0], change[1], change[1] / change[0], mean[0], mean[1], c, dimmed[0], dimmed[1],
      c / 4.0f);
  ASSERT_EQ(young[0].size(), young[1].size());
  for (std::size_t f = 0; f < young[0].size(); ++f) {
    EXPECT_TRUE(young[0][f].pixels == young[1][f].pixels) << "frame " << f << " was stabilised";
  }
  EXPECT_LT(change[1], 0.6 * change[0]) << "stabilisation did not steady the still view";
  EXPECT_NEAR(mean[1] / c, 1.0, 0.01);
  EXPECT_NEAR(dimmed[1] / dimmed[0], 1.0, 0.05) << "stabilisation lags a light that changed";
}

// A pixel that stays lit among dark neighbours is not held black (static camera, temporal only):
// after 6 black frames one surface pixel gets c every frame while its neighbours stay black. Its
// history is long and all black, so the first lit frame is judged by the neighbours and clamped
// to 0, as a lone firefly is; but the moments keep the sample, so from the second lit frame the
// history judges it (mean + firefly sigma lets it in) and the pixel climbs to c. Before, every
// frame met the neighbour clamp again and the pixel stayed 0 for good (cornell_lights: a penumbra
// pixel that ReSTIR lit 12 frames in a row read 0.000 denoised).
TEST_F(DenoiseGpuTest, LitPixelAmongDarkOnesIsNotHeldBlack) {
  Run run = make_run({{"atrous", "0"}});
  std::vector<std::uint8_t> mask;
  FrameSnapshot s = black_frames(run, 6, mask);
  const std::size_t lit = interior_surface_pixel(mask);
  ASSERT_NE(lit, 0u);
  const float c = 0.4f;
  ImageRGBA32F input = constant(0.0f);
  for (int k = 0; k < 3; ++k) input.pixels[4 * lit + k] = c;
  std::vector<float> shown;
  for (int f = 0; f < 40; ++f) {
    s = frozen(s);
    const ImageRGBA32F out = render(run, input, s);
    shown.push_back(out.pixels[4 * lit]);
  }
  std::printf("[denoise lit among dark] frames 1, 2, 3, 40: %.5f %.5f %.5f %.5f (c = %.5f)\n",
              shown[0], shown[1], shown[2], shown[39], c);
  EXPECT_EQ(shown[0], 0.0f) << "the first lit frame is a lone sample: the neighbours clamp it";
  EXPECT_GT(shown[1], 0.05f * c) << "the history kept no trace of the first lit frame";
  for (int f = 2; f < 40; ++f) EXPECT_GE(shown[f], shown[f - 1]) << "frame " << f + 1;
  EXPECT_NEAR(shown[39] / c, 1.0, 0.05);
}

// A pixel in shadow beside a lit surface of the same normal and material, whose samples agree,
// is not filtered into its neighbours' light once it has kDenoiseOwnSpreadHistory frames of
// history (still view; one interior surface pixel black among pixels of c): in the first frame
// only the neighbours' spread is known and the à-trous steps draw light into it, from the second
// on its own samples' spread (none) bounds the short history's variance and it stays black: the
// neighbours' samples agree too (none spread), so the bound's floor is 0. Its lit neighbours
// keep c.
TEST_F(DenoiseGpuTest, DarkPixelWhoseSamplesAgreeStaysDarkInAShortHistory) {
  std::vector<std::uint8_t> mask;
  const std::size_t dark = interior_pixel(mask);
  ASSERT_NE(dark, 0u);
  const float c = 0.4f;
  ImageRGBA32F input = constant(c);
  for (int k = 0; k < 3; ++k) input.pixels[4 * dark + k] = 0.0f;
  Run run = make_run();
  FrameSnapshot s = test::first_snapshot(level, kW, kH);
  std::vector<float> shown;
  float darkest_beside = c;
  for (int f = 0; f < 3; ++f) {
    if (f > 0) s = frozen(s);
    const ImageRGBA32F out = render(run, input, s);
    shown.push_back(out.pixels[4 * dark]);
    for (std::size_t q : {dark - 1, dark + 1, dark - kW, dark + kW}) {
      if (f > 0) darkest_beside = std::min(darkest_beside, out.pixels[4 * q]);
    }
  }
  std::printf("[denoise dark among lit] frames 1, 2, 3: %.5f %.5f %.5f; beside it at least %.5f "
              "(c = %.2f)\n",
              shown[0], shown[1], shown[2], darkest_beside, c);
  static_assert(gpu::kDenoiseOwnSpreadHistory == 2.0f && gpu::kDenoiseShortHistory == 4.0f);
  EXPECT_GT(shown[0], 0.05f * c) << "control: one frame has only the neighbours' spread";
  EXPECT_LE(shown[1], 1e-3f * c) << "two agreeing samples: the neighbours' light came in";
  EXPECT_LE(shown[2], 1e-3f * c) << "three agreeing samples: the neighbours' light came in";
  EXPECT_NEAR(darkest_beside / c, 1.0, 0.01) << "the lit pixels beside it lost light";
}

// The bound has a floor (kDenoiseOwnSpreadFloor of the smaller of the spatial estimate and the
// neighbours' own spread): samples that agree by chance among neighbours whose samples spread do
// not make a pixel noiseless. One interior surface pixel black in every frame among pixels of new
// noise each frame (mean c): without the floor its short history's variance is 0 from the second
// frame on, the à-trous steps stop at every tap and it stays exactly black; with it the
// neighbours' light still comes in, if less than in the first frame, where only their spread is
// known.
TEST_F(DenoiseGpuTest, SamplesThatAgreeByChanceAmongNoisyNeighboursAreFiltered) {
  std::vector<std::uint8_t> mask;
  const std::size_t dark = interior_pixel(mask);
  ASSERT_NE(dark, 0u);
  const float c = 0.4f;
  Run run = make_run();
  FrameSnapshot s = test::first_snapshot(level, kW, kH);
  std::vector<float> shown;
  for (int f = 0; f < 3; ++f) {
    if (f > 0) s = frozen(s);
    ImageRGBA32F input = noisy(c, static_cast<std::uint32_t>(f));
    for (int k = 0; k < 3; ++k) input.pixels[4 * dark + k] = 0.0f;
    shown.push_back(render(run, input, s).pixels[4 * dark]);
  }
  std::printf("[denoise chance agreement] frames 1, 2, 3: %.5f %.5f %.5f (c = %.2f)\n", shown[0],
              shown[1], shown[2], c);
  static_assert(gpu::kDenoiseOwnSpreadFloor == 0.05f && gpu::kDenoiseOwnSpreadHistory == 2.0f);
  EXPECT_GT(shown[0], 0.25f * c) << "control: one frame has only the neighbours' spread";
  EXPECT_GT(shown[1], 0.1f * c) << "two agreeing samples among noisy neighbours held black";
  EXPECT_GT(shown[2], 0.1f * c) << "three agreeing samples among noisy neighbours held black";
}

// The integrator's confidence weighs each frame (static camera, constant images, so every pixel
// follows the closed form through the à-trous steps): 6 black frames of M = 1, then one of c with
// M = 100 comes out as 100/106 c, where without the confidence (or with denoise.confidence off)
// it is c/7. A constant M is the same as none: c/7 again.
TEST_F(DenoiseGpuTest, ConfidenceWeighsEachFrame) {
  const float c = 0.4f;
  struct Case {
    const char* what;
    std::uint32_t dark_m, lit_m;
    bool knob;
    float expected;
  };
  const Case cases[] = {{"M 1 then 100", 1, 100, true, c * 100.0f / 106.0f},
                        {"knob off", 1, 100, false, c / 7.0f},
                        {"constant M", 50, 50, true, c / 7.0f},
                        {"no buffer", 0, 0, true, c / 7.0f}};
  for (const Case& k : cases) {
    Run run = make_run({{"confidence", k.knob ? "on" : "off"}});
    run.input->set_confidence(k.dark_m);
    std::vector<std::uint8_t> mask;
    const FrameSnapshot s = frozen(black_frames(run, 6, mask));
    run.input->set_confidence(k.lit_m);
    const Range r = masked_range(render(run, constant(c), s), mask);
    std::printf("[denoise confidence] %s: surfaces %.5f..%.5f (expected %.5f)\n", k.what, r.lo,
                r.hi, k.expected);
    EXPECT_NEAR(r.lo, k.expected, 1e-4f) << k.what;
    EXPECT_NEAR(r.hi, k.expected, 1e-4f) << k.what;
  }
}

// One frame of low confidence weighs little and leaves the history's worth: after 6 black frames
// of M = 100, a frame of c with M = 1 comes out at the color_alpha floor (0.1 c, since 1/601 is
// below it), and the next frame of c with M = 100 weighs 100 / (100 + 7 x 85.86) = 100/701 (the
// mean confidence 100 - 99/7), not the most of the blend. (The closed form is the temporal
// blend's: the stabilisation after the à-trous steps, which would blend in the first frame's
// output, is off; it has its own test.)
TEST_F(DenoiseGpuTest, OneLowConfidenceFrameKeepsTheHistory) {
  const float c = 0.4f;
  Run run = make_run({{"stabilize", "0"}});
  run.input->set_confidence(100);
  std::vector<std::uint8_t> mask;
  FrameSnapshot s = black_frames(run, 6, mask);
  const float expected[2] = {0.1f * c, 0.1f * c + 0.9f * c * 100.0f / 701.0f};
  for (int k = 0; k < 2; ++k) {
    run.input->set_confidence(k == 0 ? 1 : 100);
    s = frozen(s);
    const Range r = masked_range(render(run, constant(c), s), mask);
    std::printf("[denoise confidence dip] frame %d: surfaces %.5f..%.5f (expected %.5f)\n", k, r.lo,
                r.hi, expected[k]);
    EXPECT_NEAR(r.lo, expected[k], 1e-4f);
    EXPECT_NEAR(r.hi, expected[k], 1e-4f);
  }
}

// ReSTIR hands its reservoirs' M to the denoiser (Integrator::sample_confidence, wired through
// FrameRenderer on the default visibility backend): on cornell_lights the denoised frames with
// the confidence on and off differ (over 1% of the pixels after 6 frames; both finite). Were the
// buffer not handed over, the knob would change nothing.
TEST_F(DenoiseGpuTest, RestirHandsItsConfidenceToTheDenoiser) {
  auto cornell = std::make_shared<const Level>(load_level_argument("cornell_lights"));
  const FrameSnapshot first = test::first_snapshot(cornell, kW, kH);
  auto last_frame = [&](const char* confidence) {
    RenderHarness h(device, shaders, cornell, test::make_restir(device, shaders, {}), kW, kH);
    h.renderer().set_output(lighting::FrameOutput::Denoised);
    h.renderer().set_denoise_settings(
        lighting::make_denoise_settings("balanced", {{"confidence", confidence}}));
    FrameSnapshot s = first;
    ImageRGBA32F out;
    for (int f = 0; f < 6; ++f) {
      if (f > 0) s = frozen(s);
      out = h.render(s);
    }
    return out;
  };
  const ImageRGBA32F on = last_frame("on");
  const ImageRGBA32F off = last_frame("off");
  ASSERT_TRUE(test::all_finite(on));
  ASSERT_TRUE(test::all_finite(off));
  std::size_t differ = 0;
  for (std::size_t p = 0; p < on.pixels.size() / 4; ++p) {
    differ += std::abs(on.pixels[4 * p] - off.pixels[4 * p]) > 1e-6f * (1.0f + off.pixels[4 * p]);
  }
  std::printf("[denoise restir confidence] %zu of %u pixels differ\n", differ, kW * kH);
  EXPECT_GT(differ, kW * kH / 100);
}

}  // namespace
}  // namespace lantern::denoise_test
