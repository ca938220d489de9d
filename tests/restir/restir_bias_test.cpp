// ReSTIR's bias on lit surfaces, resolved: per scene and bias-correction mode, independent runs
// of F frames of a static view, S renderers with distinct seeds (>= 8) x R runs each (every run
// starts with a camera cut, so it reuses no history, and draws its own random numbers); each
// run's error is the relative difference of its frame-mean radiance, summed over the lit
// non-emitter pixels, from the converged reference integrator's. Frames of one run are a Markov
// chain (temporal reuse), so the standard error sigma comes from the spread between runs (batch
// means, one batch per run), plus the reference's own (its frames are independent). Pixels: those
// whose read-back G-buffer emission is zero (not an emitter seen directly: those pixels are the
// same in every integrator and would swamp the lighting), not sky, and whose reference radiance
// is positive.
//
// Asserted for balance, pairwise, bsdf, local-bsdf, glossy-bsdf, permuted, temporal-neighbours
// and stride-2 (kModes; stride-2 in CI on cornell_lights only, study's `ci_skips`): the run resolves the tolerance (kSigmas sigma < tolerance, else
// the test fails saying so) and the bias is within kSigmas sigma of zero. kSigmas is 4, not 3: a
// CI run makes about 25 such checks, and at 3 sigma one of them fails by chance in ~7% of runs
// (it happened: `bsdf` on the room read -0.41% against 3 sigma 0.39%, and the resolving study
// then read +0.03% +- 0.20%); at 4 sigma ~0.2%. The printouts keep 3 sigma, the usual figure. A
// 1% gain injected into restir.shade reads +0.63..+1.16% against 4 sigma of 0.32..0.59%
// (balance and pairwise on cornell_lights and the room) and fails all four checks. `none` is
// known to be biased dark where a neighbour's target is zero and the canonical pixel's is not
// (its 1/M weights ignore that); its bias is printed and only what is true of it asserted: it
// never exceeds the reference by more than kSigmas sigma.
//
// CI: 1% at 96x54 (kCi below, ~25 s a scene). The resolving study (0.5%, kStudy: more runs, longer
// chains, a larger image) is scripts/bias_study.sh: LANTERN_BIAS_STUDY=1 plus the LANTERN_BIAS_*
// overrides of study_params(); LANTERN_BIAS_MODES picks configurations (t-M1 only when named),
// LANTERN_BIAS_TRACE=1 prints every frame's error.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "engine/core/error.h"
#include "lighting/restir/restir_settings.h"
#include "shared/restir.h"
#include "shared/scene.h"
#include "tests/restir/restir_test_support.h"
#include "tests/runtime/gpu_test_support.h"

namespace lantern {
namespace {

using runtime::ImageRGBA32F;
using test::RenderHarness;

// One study's size. Each field has a LANTERN_BIAS_<NAME> environment override.
struct StudyParams {
  std::uint32_t width;
  std::uint32_t height;
  std::uint32_t seeds;       // ReSTIR renderers (distinct seeds) per configuration
  std::uint32_t chains;      // independent runs per renderer, each started by a camera cut
  std::uint32_t frames;      // frames per run
  std::uint32_t ref_spp;     // reference samples per pixel per frame
  std::uint32_t ref_frames;  // reference frames (independent)
  double tolerance;          // relative bias the run must resolve and stay within
};

// How many standard errors a bias may read before a check fails (the header: the checks are many).
constexpr double kSigmas = 4.0;

constexpr StudyParams kCi{.width = 96, .height = 54, .seeds = 8, .chains = 8, .frames = 8,
                          .ref_spp = 64, .ref_frames = 32, .tolerance = 0.01};
constexpr StudyParams kStudy{.width = 128, .height = 72, .seeds = 16, .chains = 4, .frames = 64,
                             .ref_spp = 64, .ref_frames = 64, .tolerance = 0.005};

std::uint32_t env_uint(const char* name, std::uint32_t fallback) {
  const char* v = std::getenv(name);
  if (v == nullptr) return fallback;
  char* end = nullptr;
  const unsigned long n = std::strtoul(v, &end, 10);
  if (end == v || *end != '\0' || n == 0 || n > 100000)
    throw InputError(std::string(name) + "=" + v + ": expected an integer in 1..100000");
  return static_cast<std::uint32_t>(n);
}

double env_double(const char* name, double fallback) {
  const char* v = std::getenv(name);
  if (v == nullptr) return fallback;
  char* end = nullptr;
  const double x = std::strtod(v, &end);
  if (end == v || *end != '\0' || !(x > 0.0 && x < 1.0))
    throw InputError(std::string(name) + "=" + v + ": expected a fraction in (0, 1), e.g. 0.005");
  return x;
}

StudyParams study_params() {
  const bool study = std::getenv("LANTERN_BIAS_STUDY") != nullptr;
  StudyParams p = study ? kStudy : kCi;
  p.width = env_uint("LANTERN_BIAS_WIDTH", p.width);
  p.height = env_uint("LANTERN_BIAS_HEIGHT", p.height);
  p.seeds = env_uint("LANTERN_BIAS_SEEDS", p.seeds);
  p.chains = env_uint("LANTERN_BIAS_RUNS", p.chains);
  p.frames = env_uint("LANTERN_BIAS_FRAMES", p.frames);
  p.ref_spp = env_uint("LANTERN_BIAS_REF_SPP", p.ref_spp);
  p.ref_frames = env_uint("LANTERN_BIAS_REF_FRAMES", p.ref_frames);
  p.tolerance = env_double("LANTERN_BIAS_TOLERANCE", p.tolerance);
  if (p.seeds < 8) throw InputError("LANTERN_BIAS_SEEDS: at least 8 independent runs");
  return p;
}

// A room with occluders: a floor and back wall lit by a bright spot and a dim point light that
// a row of pillars and a hovering slab shadow, plus a strip of emissive quads (radiances over
// 10^3) behind a low wall, so most floor pixels see some lights and not others: spatial
// neighbours' targets differ, and are zero where a light is behind the surface.
const char* kOccludersJson = R"({
  "materials": {
    "white": { "base_color": [0.7, 0.7, 0.7], "roughness": 0.8 },
    "grey":  { "base_color": [0.4, 0.45, 0.5], "roughness": 0.5 },
    "panel": { "base_color": [0.02, 0.02, 0.02], "roughness": 0.9 }
  },
  "primitives": [
    { "type": "plane", "name": "floor", "size": [6, 6], "material": "white" },
    { "type": "plane", "name": "back", "size": [6, 3], "material": "white",
      "translation": [0, 1.5, -2], "rotation_deg": [90, 0, 0] },
    { "type": "box", "name": "pillar_a", "size": [0.3, 1.6, 0.3], "material": "grey",
      "translation": [-1.2, 0.8, -0.6] },
    { "type": "box", "name": "pillar_b", "size": [0.3, 1.6, 0.3], "material": "grey",
      "translation": [0.0, 0.8, -0.9] },
    { "type": "box", "name": "pillar_c", "size": [0.3, 1.6, 0.3], "material": "grey",
      "translation": [1.1, 0.8, -0.4] },
    { "type": "box", "name": "slab", "size": [1.4, 0.1, 0.8], "material": "grey",
      "translation": [0.4, 1.3, 0.6] },
    { "type": "emissive_quad_grid", "name": "sign", "material": "panel",
      "origin": [-0.3, 1.6, -1.99], "u": [0.6, 0, 0], "v": [0, 0.3, 0], "counts": [1, 1],
      "size": [0.5, 0.2], "color": [1.0, 0.8, 0.6], "radiance": { "min": 20, "max": 20 } }
  ],
  "lights": [
    { "type": "spot", "name": "spot", "position": [1.5, 3.0, 1.5], "target": [-0.5, 0, -0.5],
      "intensity": 25, "inner_cone_deg": 30, "outer_cone_deg": 45 },
    { "type": "point", "name": "bulb", "position": [-1.0, 2.2, 0.8], "intensity": 8 },
    { "type": "point", "name": "low", "position": [0.6, 0.5, -1.6], "color": [0.6, 0.8, 1.0],
      "intensity": 2 }
  ],
  "camera": { "position": [0, 2.2, 3.4], "target": [0, 0.6, -0.6], "yfov_deg": 45 }
})";

// The occluded room with its sign split into 40 x 30 emissive quads (2400 triangles + 3 analytic
// lights: more than one presampling tile, so restir.presample's tiles feed the light candidates).
std::string many_lights_json() {
  std::string json = kOccludersJson;
  const std::string one = R"("u": [0.6, 0, 0], "v": [0, 0.3, 0], "counts": [1, 1],
      "size": [0.5, 0.2])";
  const std::string many = R"("u": [0.0125, 0, 0], "v": [0, 0.0067, 0], "counts": [40, 30],
      "size": [0.0125, 0.0067])";
  json.replace(json.find(one), one.size(), many);
  return json;
}

// The occluded room with a field of 30 x 20 small emissive quads 10 cm above the floor, facing it
// (1200 triangles: presampling, the local lists and the light grid candidates on): the floor
// between the quads is lit mostly by the few beside it, which the light grid draws at ~100x the
// density power draws have, so the balance heuristic gives the grid's density most of the weight
// there.
std::string near_lights_json() {
  std::string json = kOccludersJson;
  const std::string sign_end = R"("radiance": { "min": 20, "max": 20 } })";
  const std::string field = R"(,
    { "type": "emissive_quad_grid", "name": "floor_field", "material": "panel",
      "origin": [-1.95, 0.1, -1.3], "u": [0.13, 0, 0], "v": [0, 0, 0.13], "counts": [30, 20],
      "size": [0.05, 0.05], "color": [1.0, 0.9, 0.7], "radiance": { "min": 10, "max": 40 } })";
  json.insert(json.find(sign_end) + sign_end.size(), field);
  return json;
}

// ReSTIR configurations: the balanced preset with these settings.
struct Mode {
  const char* name;
  std::vector<std::pair<std::string, std::string>> settings;
  bool unbiased;  // asserted within the tolerance; else only "never above the reference"
  bool ci;        // run by default; the others only when named in LANTERN_BIAS_MODES
};
const Mode kModes[] = {
    {"balance", {{"bias_correction", "balance"}}, true, true},
    {"pairwise", {{"bias_correction", "pairwise"}}, true, true},
    {"none", {{"bias_correction", "none"}}, false, true},
    // One BSDF candidate MIS'd with the light candidates; then the same with the local light
    // lists and the light grid candidates on whatever the light count and spread
    // (local_min_lights 1, light_spread 1000: cornell_lights and the room draw their slots from
    // the alias table, many_lights from presampled tiles), where the balance heuristic over the
    // three strategies weighs the light strategy's own density while a candidate carries its
    // slot's contribution weight.
    {"bsdf", {{"bsdf_candidates", "1"}}, true, true},
    {"local-bsdf", {{"bsdf_candidates", "1"}, {"local_min_lights", "1"}, {"light_spread", "1000"}},
     true, true},
    // BSDF candidates on the glossier surfaces only (gloss 0.2: the room's pillars and slab and
    // cornell_lights' glossy box, not the walls and floors), so reuse mixes reservoirs whose
    // initial MIS weighed one strategy with ones that weighed two.
    {"glossy-bsdf", {{"bsdf_candidates", "1"}, {"bsdf_min_gloss", "0.2"}}, true, true},
    // Temporal permutation (what the denoiser's frames use): each pixel's history comes from a
    // neighbour, which pairwise MIS weighs as such. The balance heuristic's: study only.
    {"permuted", {{"temporal_permutation", "on"}}, true, true},
    // Spatiotemporal reuse in restir.temporal alone: last frame's neighbours around the
    // reprojected pixel are more domains, each weighed at its own (last frame's) surface. The
    // balance heuristic's: study only.
    {"temporal-neighbours", {{"temporal_neighbours", "4"}, {"spatial_passes", "0"}}, true, true},
    // One reservoir per 2x2 pixels: the chain resamples for one representative pixel a frame, and
    // every other pixel resamples a similar cell's reservoir with one light candidate of its own
    // (restir_shade.comp's resample_for_pixel), weighed by the balance heuristic.
    {"stride-2", {{"reservoir_stride", "2"}}, true, true},
    {"balance-temporal-neighbours",
     {{"bias_correction", "balance"}, {"temporal_neighbours", "4"}, {"spatial_passes", "0"}}, true,
     false},
    {"balance-permuted", {{"bias_correction", "balance"}, {"temporal_permutation", "on"}}, true,
     false},
    // Study only (named in LANTERN_BIAS_MODES): each stage alone. Temporal reuse only, one
    // candidate: the longest-lived histories (the empty-history bug read +18% there on the CPU
    // chains); M cap 1; spatial only; no reuse (plain RIS: checks the reference itself).
    {"t-M1", {{"spatial_passes", "0"}, {"light_candidates", "1"}}, true, false},
    {"t-cap1", {{"spatial_passes", "0"}, {"m_cap", "1"}}, true, false},
    {"temporal", {{"spatial_passes", "0"}}, true, false},
    {"spatial", {{"temporal", "off"}, {"bias_correction", "pairwise"}}, true, false},
    {"spatial-b", {{"temporal", "off"}, {"bias_correction", "balance"}}, true, false},
    {"ris", {{"temporal", "off"}, {"spatial_passes", "0"}}, true, false},
    // Local light lists (on in balanced where a level has > 1024 lights) with many draws per
    // slot, and off.
    {"local-32", {{"local_candidates", "32"}}, true, false},
    {"no-local", {{"local_candidates", "0"}}, true, false},
    // Light grid candidates (on in every preset where the local lists are: many_lights here,
    // and every scene in local-bsdf), and off.
    {"grid-4", {{"grid_candidates", "4"}}, true, false},
    {"no-grid", {{"grid_candidates", "0"}}, true, false},
};

// LANTERN_BIAS_MODES=balance,none,t-M1 selects modes (default: those marked ci).
bool mode_selected(const Mode& mode) {
  const std::string name = mode.name;
  const char* only = std::getenv("LANTERN_BIAS_MODES");
  if (only == nullptr) return mode.ci;
  const std::string list = only;
  std::size_t begin = 0;
  while (begin <= list.size()) {
    const std::size_t end = std::min(list.find(',', begin), list.size());
    if (list.compare(begin, end - begin, name) == 0) return true;
    begin = end + 1;
  }
  return false;
}

class RestirBiasTest : public runtime::test::GpuTest {
 protected:
  runtime::ShaderLibrary shaders;

  // Lit non-emitter channels of `image` summed over `mask`.
  static double lit_sum(const ImageRGBA32F& image, const std::vector<std::uint8_t>& mask) {
    double sum = 0.0;
    for (std::size_t p = 0; p < mask.size(); ++p)
      if (mask[p])
        sum += double(image.pixels[4 * p]) + image.pixels[4 * p + 1] + image.pixels[4 * p + 2];
    return sum;
  }

  // With `jitter`, the G-buffer samples every frame at its sub-pixel Halton offset (as while
  // upscaling) for the reference and ReSTIR alike: both average the same 8 sample positions (32
  // reference frames, 8-frame runs), so their expectations are equal, and ReSTIR's temporal reuse
  // must stay unbiased with motion vectors that carry the jitter. Only the balance mode runs then.
  // `level_settings` apply after the preset and before each mode's (a level's own "settings").
  // `ci_skips`: modes that this scene's CI run leaves to the study (named in LANTERN_BIAS_MODES,
  // they run). `min_tolerance`: the finest bias this scene's runs are asked to resolve, where
  // one run spreads too far for the study's tolerance (near_lights).
  void study(const char* scene, std::shared_ptr<const Level> level, bool jitter = false,
             const std::vector<std::pair<std::string, std::string>>& level_settings = {},
             const std::vector<std::string>& ci_skips = {}, double min_tolerance = 0.0) {
    StudyParams p = study_params();
    p.tolerance = std::max(p.tolerance, min_tolerance);
    const FrameSnapshot first = test::first_snapshot(level, p.width, p.height);
    const std::size_t pixels = std::size_t{p.width} * p.height;

    // Reference: the reference integrator's frames (independent), kept for the lit sums once the
    // mask is known; the G-buffer of its first frame chooses the pixels.
    std::vector<ImageRGBA32F> ref_images;
    lighting::GBufferTexels gbuffer;
    auto clock_start = std::chrono::steady_clock::now();
    auto seconds = [&clock_start]() {
      const auto now = std::chrono::steady_clock::now();
      const double s = std::chrono::duration<double>(now - clock_start).count();
      clock_start = now;
      return s;
    };
    {
      RenderHarness h(device, shaders, level,
                      lighting::make_integrator(device, shaders,
                                                {.name = "reference", .spp = p.ref_spp}),
                      p.width, p.height, 7);
      if (jitter) h.renderer().set_jitter(lighting::FrameRenderer::Jitter::On);
      FrameSnapshot s = first;
      for (std::uint32_t f = 0; f < p.ref_frames; ++f) {
        ref_images.push_back(h.render(s, f == 0 ? &gbuffer : nullptr));
        s = frozen(s);
      }
    }
    runtime::ImageAccumulator acc;
    for (const ImageRGBA32F& img : ref_images) acc.add(img);
    const ImageRGBA32F reference = acc.mean();
    std::vector<std::uint8_t> mask(pixels, 0);
    std::size_t emitters = 0, sky = 0, dark = 0, edges = 0;
    // With jitter, a pixel counts only when its 3x3 neighbourhood is one non-emitting surface:
    // the sub-pixel offsets then never move an emitter or the sky into it, so a frame's lit sum
    // varies by noise, not by which surface the phase lands on.
    auto interior = [&](std::size_t i) {
      const auto x = static_cast<std::int64_t>(i % p.width), y = static_cast<std::int64_t>(i / p.width);
      for (std::int64_t dy = -1; dy <= 1; ++dy)
        for (std::int64_t dx = -1; dx <= 1; ++dx) {
          const std::int64_t qx = x + dx, qy = y + dy;
          if (qx < 0 || qy < 0 || qx >= p.width || qy >= p.height) return false;
          const std::size_t q = static_cast<std::size_t>(qy) * p.width + static_cast<std::size_t>(qx);
          const glm::vec4 eq = gbuffer.emission[q];
          if (gbuffer.ids[q].x != gbuffer.ids[i].x || eq.x != 0.0f || eq.y != 0.0f || eq.z != 0.0f)
            return false;
        }
      return true;
    };
    for (std::size_t i = 0; i < pixels; ++i) {
      const glm::vec4 e = gbuffer.emission[i];
      const double r = double(reference.pixels[4 * i]) + reference.pixels[4 * i + 1] +
                       reference.pixels[4 * i + 2];
      if (gbuffer.ids[i].x == gpu::kNoInstance) {
        ++sky;
      } else if (e.x != 0.0f || e.y != 0.0f || e.z != 0.0f) {
        ++emitters;
      } else if (!(r > 0.0)) {
        ++dark;
      } else if (jitter && !interior(i)) {
        ++edges;
      } else {
        mask[i] = 1;
      }
    }
    const std::size_t lit = test::count(mask);
    ASSERT_GT(lit, pixels / 4) << scene << ": most pixels must be lit non-emitters";
    ASSERT_GT(emitters, 0u) << scene << ": the scene's emitters must be seen and left out";
    double ref = 0.0, ref2 = 0.0;
    for (const ImageRGBA32F& img : ref_images) {
      const double v = lit_sum(img, mask);
      ref += v;
      ref2 += v * v;
    }
    ref /= p.ref_frames;
    const double ref_se =
        std::sqrt(std::max(ref2 / p.ref_frames - ref * ref, 0.0) / (p.ref_frames - 1.0)) / ref;
    std::printf("[restir bias] %s %ux%u: %zu lit non-emitter pixels (%zu emitter, %zu sky, %zu "
                "unlit, %zu edge left out); reference %u x %u spp, relative standard error %.4f%% "
                "(%.1f s)\n",
                scene, p.width, p.height, lit, emitters, sky, dark, edges, p.ref_frames, p.ref_spp,
                100.0 * ref_se, seconds());

    // One renderer per seed; in it, per mode, `chains` runs, each started by a camera cut (no
    // history: restir.temporal reuses nothing, CameraCutUsesNoHistory) and drawing its own random
    // numbers (they hash the frame index, which never repeats in a renderer): every run is an
    // independent batch. The modes share the renderer (the mode is a push constant).
    std::vector<const Mode*> modes;
    const bool named = std::getenv("LANTERN_BIAS_MODES") != nullptr;
    for (const Mode& mode : kModes) {
      const bool skipped =
          !named && std::find(ci_skips.begin(), ci_skips.end(), mode.name) != ci_skips.end();
      if (mode_selected(mode) && !skipped &&
          (!jitter || named || std::string(mode.name) == "balance"))
        modes.push_back(&mode);
    }
    ASSERT_FALSE(modes.empty()) << "LANTERN_BIAS_MODES names no mode this test runs";
    std::vector<std::vector<double>> errors(modes.size());
    const bool trace = std::getenv("LANTERN_BIAS_TRACE") != nullptr;
    for (std::uint32_t seed = 0; seed < p.seeds; ++seed) {
      RenderHarness h(device, shaders, level, test::make_restir(device, shaders, {}), p.width,
                      p.height, 1000u + seed);
      if (jitter) h.renderer().set_jitter(lighting::FrameRenderer::Jitter::On);
      const std::vector<std::pair<std::string, std::string>> balanced =
          h.integrator().describe_settings();
      for (std::uint32_t chain = 0; chain < p.chains; ++chain) {
        for (std::size_t m = 0; m < modes.size(); ++m) {
          h.integrator().apply_settings(balanced);  // the preset, the level's, this mode's
          h.integrator().apply_settings(level_settings);
          h.integrator().apply_settings(modes[m]->settings);
          FrameSnapshot s = first;
          s.camera_cut = true;
          double sum = 0.0;
          for (std::uint32_t f = 0; f < p.frames; ++f) {
            const ImageRGBA32F img = h.render(s);
            ASSERT_TRUE(test::all_finite(img))
                << scene << " " << modes[m]->name << " seed " << seed;
            const double v = lit_sum(img, mask);
            sum += v;
            if (trace) std::printf(" %+.2f", 100.0 * (v / ref - 1.0));
            s = frozen(s);
          }
          if (trace) std::printf(" <- %s seed %u run %u\n", modes[m]->name, seed, chain);
          errors[m].push_back(sum / p.frames / ref - 1.0);
        }
      }
    }
    std::printf("[restir bias] %s: %u seeds x %u runs x %u frames per mode (%.1f s)\n", scene,
                p.seeds, p.chains, p.frames, seconds());
    for (std::size_t m = 0; m < modes.size(); ++m) {
      const Mode& mode = *modes[m];
      const std::vector<double>& run_error = errors[m];
      const double n = double(run_error.size());
      double bias = 0.0, var = 0.0;
      for (double e : run_error) bias += e / n;
      for (double e : run_error) var += (e - bias) * (e - bias) / (n - 1.0);
      const double sigma = std::sqrt(var / n + ref_se * ref_se);
      std::printf("[restir bias] %s %-8s bias %+.3f%% +- %.3f%% (3 sigma; one run's sd %.3f%%)\n",
                  scene, mode.name, 100.0 * bias, 300.0 * sigma, 100.0 * std::sqrt(var));
      std::fflush(stdout);
      if (mode.unbiased) {
        EXPECT_LT(kSigmas * sigma, p.tolerance)
            << scene << " " << mode.name << ": this run cannot resolve a bias of "
            << 100.0 * p.tolerance << "%: " << kSigmas << " sigma = " << 100.0 * kSigmas * sigma
            << "% (more LANTERN_BIAS_RUNS or LANTERN_BIAS_SEEDS)";
        EXPECT_LE(std::abs(bias), kSigmas * sigma)
            << scene << " " << mode.name << ": biased by " << 100.0 * bias << "% (" << kSigmas
            << " sigma " << 100.0 * kSigmas * sigma << "%, tolerance " << 100.0 * p.tolerance
            << "%)";
      } else {
        EXPECT_LE(bias, kSigmas * sigma)
            << scene << " " << mode.name << ": brighter than the reference by " << 100.0 * bias
            << "% (" << kSigmas << " sigma " << 100.0 * kSigmas * sigma << "%)";
      }
    }
  }
};

TEST_F(RestirBiasTest, CornellLightsLitSurfaces) {
  study("cornell_lights", std::make_shared<const Level>(load_level_argument("cornell_lights")));
}

TEST_F(RestirBiasTest, CornellLightsLitSurfacesWithJitter) {
  ASSERT_EQ(study_params().frames % 8, 0u) << "runs must cover the 8 jitter phases";
  ASSERT_EQ(study_params().ref_frames % 8, 0u);
  study("cornell_lights+jitter",
        std::make_shared<const Level>(load_level_argument("cornell_lights")), true);
}

TEST_F(RestirBiasTest, OccludedRoomLitSurfaces) {
  // stride-2: one run's spread here is 1.7–1.9%, so CI's 64 runs put 4 sigma at 0.85–0.96%, too
  // near the 1% they must resolve to pass every time; the study resolves it (README).
  study("occluders", test::level_from_json("bias_occluders", kOccludersJson), false, {},
        {"stride-2"});
}

// Presampled tiles and the local light lists (balanced's light candidates there come from them;
// the sign's quads are alike from the room, so its measured light spread would turn the lists off
// and take fewer tiles: the level states a spread that keeps both).
TEST_F(RestirBiasTest, ManyLightsPresampledLitSurfaces) {
  const auto level = test::level_from_json("bias_many_lights", many_lights_json());
  std::size_t triangles = 0;
  for (const Instance& inst : level->instances)
    if (level->materials[inst.material].emissive())
      triangles += level->meshes[inst.mesh].triangle_count();
  ASSERT_GT(triangles, gpu::kRestirPresampleTileSize) << "presampling must be on";
  ASSERT_GT(lighting::restir_preset("balanced").presample_tiles, 0u);
  ASSERT_GT(lighting::restir_preset("balanced").local_candidates, 0u) << "local lists must be on";
  // stride-2: one run's spread here is 2.3–2.5% (pairwise's 1.6%), so CI's 64 runs put 4 sigma
  // at 1.16–1.26%, above the 1% they must resolve; the study resolves it (README, "One reservoir
  // per 2×2 pixels").
  study("many_lights", level, false, {{"light_spread", "1000"}}, {"stride-2"});
}

// The light grid candidates where they carry much of the light (near_lights_json). One run's
// frame mean spreads 2.2-3.8% here (the quads' near field; 5.0-7.8% before the grid weighed its
// cells by power and distance), so CI's 64 runs resolve 2% (3 sigma 0.9-1.5%), not 1%: enough
// for a grid density 30% off, which reads -15.7% +- 0.9% (pairwise) and fails.
TEST_F(RestirBiasTest, NearLightsGridLitSurfaces) {
  const auto level = test::level_from_json("bias_near_lights", near_lights_json());
  ASSERT_GT(lighting::restir_preset("balanced").grid_candidates, 0u) << "grid candidates must be on";
  study("near_lights", level, false, {{"light_spread", "1000"}}, {"stride-2"}, 0.02);
}

}  // namespace
}  // namespace lantern
