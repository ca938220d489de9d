// The denoise.* chain end to end on lavapipe through FrameRenderer (output Denoised), fed images
// the test chooses by a test integrator (ImageIntegrator: copies a host image into the HDR
// buffer), over the real G-buffer of a small grey scene: energy preservation on a constant and
// on a noisy image of known mean, history rejected across a camera cut and a disocclusion
// (exact images), no NaN/Inf from non-finite input. The fixture checks validation ran clean.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <limits>
#include <tuple>

#include "lighting/denoise/denoise_pass.h"
#include "lighting/denoise/denoise_settings.h"
#include "lighting/upscale/upscaler.h"
#include "lighting/visibility/visibility_backend.h"
#include "runtime/gpu/buffer.h"
#include "runtime/graph/pass_context.h"
#include "shared/pixel_groups.h"
#include "shared/reservoir_pack.h"
#include "shared/scene.h"
#include "tests/restir/restir_test_support.h"
#include "tests/runtime/gpu_test_support.h"

namespace lantern {
namespace {

using runtime::ImageRGBA32F;
using test::RenderHarness;

constexpr std::uint32_t kW = 96;
constexpr std::uint32_t kH = 54;

// An integrator whose "radiance" is whatever image the test set last: a Transfer pass copying it
// from a host-visible buffer into hdr. With set_confidence(M > 0) it also hands the denoiser a
// host-written confidence buffer (PackedReservoirs whose M is M everywhere), as ReSTIR does.
class ImageIntegrator final : public lighting::Integrator {
 public:
  ImageIntegrator(runtime::Device& device, std::uint32_t w, std::uint32_t h)
      : upload_(device, {.size = std::uint64_t{w} * h * 16,
                         .usage = VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                         .memory = runtime::MemoryUsage::Upload,
                         .name = "test.image_upload"}),
        confidence_buffer_(device, {.size = std::uint64_t{w} * h * sizeof(gpu::PackedReservoir),
                                    .usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                    .memory = runtime::MemoryUsage::Upload,
                                    .name = "test.confidence"}),
        pixels_(std::size_t{w} * h) {}
  const char* name() const override { return "test.image"; }
  void warm_up() override {}
  std::vector<std::pair<std::string, std::string>> describe_settings() const override {
    return {};
  }
  void apply_settings(const std::vector<std::pair<std::string, std::string>>&) override {}
  void set(const ImageRGBA32F& image) {
    std::memcpy(upload_.mapped(), image.pixels.data(), image.pixels.size() * sizeof(float));
  }
  // Every pixel's M from the next frame on; 0: no confidence buffer (every frame the same).
  void set_confidence(std::uint32_t m) {
    confidence_m_ = m;
    std::vector<gpu::PackedReservoir> records(pixels_, gpu::PackedReservoir{0u, 0u, 0.0f, m});
    std::memcpy(confidence_buffer_.mapped(), records.data(),
                records.size() * sizeof(gpu::PackedReservoir));
  }
  runtime::graph::BufferHandle sample_confidence() const override { return confidence_; }
  runtime::graph::BufferHandle add_passes(runtime::graph::RenderGraph& graph,
                                          const lighting::FrameInputs& inputs,
                                          runtime::graph::BufferHandle hdr) override {
    struct Copy {
      runtime::graph::BufferHandle src, dst;
    };
    // The first width x height pixels of the image (all of it at the output size).
    const VkDeviceSize bytes = VkDeviceSize{inputs.width} * inputs.height * 16;
    runtime::graph::ImportInfo host_written;
    host_written.read_only = true;
    host_written.initial = runtime::graph::AccessState{
        VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_WRITE_BIT, VK_IMAGE_LAYOUT_UNDEFINED};
    confidence_ = confidence_m_ == 0
                      ? runtime::graph::BufferHandle{}
                      : graph.import_buffer(confidence_buffer_.name(), confidence_buffer_.handle(),
                                            {confidence_buffer_.size()}, host_written);
    const runtime::graph::BufferHandle src =
        graph.import_buffer(upload_.name(), upload_.handle(), {upload_.size()}, host_written);
    return graph
        .add_pass<Copy>(
            "test.image", runtime::graph::PassKind::Transfer,
            [&](runtime::graph::PassBuilder& b, Copy& d) {
              d.src = src;
              b.read(src, runtime::graph::Access::TransferSrc);
              d.dst = b.write(hdr, runtime::graph::Access::TransferDst);
            },
            [bytes](runtime::graph::PassContext& ctx, const Copy& d) {
              const VkBufferCopy region{0, 0, bytes};
              vkCmdCopyBuffer(ctx.cmd(), ctx.buffer(d.src), ctx.buffer(d.dst), 1, &region);
            })
        .dst;
  }

 private:
  runtime::Buffer upload_;
  runtime::Buffer confidence_buffer_;
  std::size_t pixels_;
  std::uint32_t confidence_m_ = 0;
  runtime::graph::BufferHandle confidence_;
};

// A grey room corner (floor and wall, one Lambertian albedo) with a box in front of the wall.
constexpr const char* kScene = R"({
  "materials": { "grey": { "base_color": [0.5, 0.5, 0.5], "roughness": 0.8 } },
  "primitives": [
    { "type": "plane", "name": "floor", "size": [6, 6], "material": "grey" },
    { "type": "plane", "name": "wall", "size": [6, 6], "material": "grey",
      "translation": [0, 0, -2], "rotation_deg": [90, 0, 0] },
    { "type": "box", "name": "box", "size": [0.8, 1.2, 0.8], "material": "grey",
      "translation": [0, 0.6, -0.5] } ],
  "lights": [ { "type": "point", "name": "lamp", "position": [0, 2, 1], "intensity": 1 } ],
  "camera": { "position": [0, 1.2, 3], "target": [0, 0.6, -1], "yfov_deg": 60 } })";

std::size_t instance_index(const Level& level, const std::string& name) {
  for (std::size_t i = 0; i < level.instances.size(); ++i)
    if (level.instances[i].name == name) return i;
  throw RuntimeError("denoise test scene has no " + name);
}

// Radiance c on every pixel (sky included).
ImageRGBA32F constant(float c, std::uint32_t w = kW, std::uint32_t h = kH) {
  ImageRGBA32F image(w, h);
  for (std::size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = i % 4 == 3 ? 1.0f : c;
  return image;
}

// c x u, u uniform in [0, 2) per pixel, channel and frame (mean c; a hash, reproducible).
ImageRGBA32F noisy(float c, std::uint32_t frame) {
  ImageRGBA32F image(kW, kH);
  for (std::size_t i = 0; i < image.pixels.size(); ++i) {
    std::uint32_t h = static_cast<std::uint32_t>(i) * 747796405u + frame * 2891336453u + 1u;
    h = ((h >> ((h >> 28u) + 4u)) ^ h) * 277803737u;
    h = (h >> 22u) ^ h;
    image.pixels[i] = i % 4 == 3 ? 1.0f : c * 2.0f * static_cast<float>(h >> 8) / 16777216.0f;
  }
  return image;
}

// An input for an internal size below the output: w x h pixels of which the first in_w x in_h,
// rows of in_w, are read (what the renderer reads at that internal size), grey value(x, y) at
// internal pixel (x, y), alpha 1.
template <class Value>
ImageRGBA32F internal_image(std::uint32_t w, std::uint32_t h, std::uint32_t in_w,
                            std::uint32_t in_h, Value value) {
  ImageRGBA32F image(w, h);
  for (std::uint32_t y = 0; y < in_h; ++y) {
    for (std::uint32_t x = 0; x < in_w; ++x) {
      const float v = value(x, y);
      for (int c = 0; c < 4; ++c)
        image.pixels[4 * (std::size_t{y} * in_w + x) + c] = c == 3 ? 1.0f : v;
    }
  }
  return image;
}

// Pixels that show a surface (not sky).
std::vector<std::uint8_t> surfaces(const lighting::GBufferTexels& g) {
  std::vector<std::uint8_t> mask(g.ids.size());
  for (std::size_t p = 0; p < mask.size(); ++p) mask[p] = g.ids[p].x != gpu::kNoInstance;
  return mask;
}

class DenoiseGpuTest : public runtime::test::GpuTest {
 protected:
  runtime::ShaderLibrary shaders;
  std::shared_ptr<const Level> level = test::level_from_json("denoise_corner", kScene);

  struct Run {
    ImageIntegrator* input;  // owned by the harness's renderer
    std::unique_ptr<RenderHarness> harness;
  };
  Run make_run(const std::vector<std::pair<std::string, std::string>>& denoise = {},
               std::uint32_t w = kW, std::uint32_t h = kH) {
    auto integrator = std::make_unique<ImageIntegrator>(device, w, h);
    Run run{integrator.get(), nullptr};
    run.harness = std::make_unique<RenderHarness>(device, shaders, level, std::move(integrator),
                                                  w, h);
    run.harness->renderer().set_output(lighting::FrameOutput::Denoised);
    run.harness->renderer().set_denoise_settings(lighting::make_denoise_settings("balanced", denoise));
    return run;
  }
  ImageRGBA32F render(Run& run, const ImageRGBA32F& input, const FrameSnapshot& s,
                      lighting::GBufferTexels* gbuffer = nullptr) {
    run.input->set(input);
    return run.harness->render(s, gbuffer);
  }
  // CameraCutRejectsHistory under these denoise settings.
  void expect_cut_rejects_history(const std::vector<std::pair<std::string, std::string>>& settings);
  // `frames` black frames of the still scene from its first snapshot; returns the last snapshot
  // and the surface pixels.
  FrameSnapshot black_frames(Run& run, int frames, std::vector<std::uint8_t>& mask) {
    FrameSnapshot s = test::first_snapshot(level, kW, kH);
    lighting::GBufferTexels g;
    for (int f = 0; f < frames; ++f) {
      if (f > 0) s = frozen(s);
      (void)render(run, constant(0.0f), s, &g);
    }
    mask = surfaces(g);
    return s;
  }
};

// A surface pixel whose 8 neighbours are surfaces too, the first from the image's centre on (0
// when there is none).
std::size_t interior_surface_pixel(const std::vector<std::uint8_t>& mask) {
  for (std::uint32_t y = kH / 2; y < kH - 1; ++y) {
    for (std::uint32_t x = kW / 2; x < kW - 1; ++x) {
      bool all = true;
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) all = all && mask[(y + dy) * kW + (x + dx)];
      }
      if (all) return std::size_t{y} * kW + x;
    }
  }
  return 0;
}

// The lowest and highest red value over the masked pixels.
struct Range {
  float lo = std::numeric_limits<float>::infinity();
  float hi = -std::numeric_limits<float>::infinity();
};
Range masked_range(const ImageRGBA32F& image, const std::vector<std::uint8_t>& mask) {
  Range r;
  for (std::size_t p = 0; p < mask.size(); ++p) {
    if (!mask[p]) continue;
    r.lo = std::min(r.lo, image.pixels[4 * p]);
    r.hi = std::max(r.hi, image.pixels[4 * p]);
  }
  return r;
}

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
  std::printf("[denoise shadow line] %zu rows: line at most %.3g, beside it at least %.5f (c %.2f)\n",
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

// A camera cut drops all history: the frame after the cut is exactly (bit for bit) the first
// frame of a fresh renderer fed the same image; without the cut it is not.
TEST_F(DenoiseGpuTest, CameraCutRejectsHistory) {
  for (const char* stabilize : {"0", "0.7"}) {
    SCOPED_TRACE(std::string("stabilize ") + stabilize);
    expect_cut_rejects_history({{"stabilize", stabilize}});
  }
}

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
  for (std::size_t i = 0; i < expected.pixels.size(); ++i) differ += after_cut.pixels[i] != expected.pixels[i];
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
  s.instances[box].object_to_world =
      glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, 50.0f)) * s.instances[box].object_to_world;
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
  std::printf("[denoise disocclusion] %zu uncovered pixels (%zu = input), %zu stayed (%zu = "
              "blend)\n", uncovered, uncovered_exact, stayed, stayed_exact);
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
    s.instances[box].object_to_world =
        glm::translate(glm::mat4(1.0f), glm::vec3(dx, 0.0f, 0.0f)) * s.instances[box].object_to_world;
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
  std::printf("[denoise partial footprint] box motion %.2f..%.2f px; %zu box pixels less than 0.4 "
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
  s.instances[box].object_to_world =
      glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, 50.0f)) * s.instances[box].object_to_world;
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
    std::printf("[denoise disocclusion recovery] frame %d after: uncovered RMS %.4f mean %.4f, "
                "stayed RMS %.4f (%.2fx)\n", k, uncovered_rms, mean, stayed_rms,
                uncovered_rms / stayed_rms);
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
  std::printf("[denoise light on] first lit frame: surfaces %.5f..%.5f (c/7 = %.5f)\n", r.lo,
              r.hi, c / 7.0f);
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
  {
    Run probe = make_run();
    (void)black_frames(probe, 1, mask);
  }
  const std::size_t spike = interior_surface_pixel(mask);
  ASSERT_NE(spike, 0u);
  ImageRGBA32F input = constant(c);
  for (int k = 0; k < 3; ++k) input.pixels[4 * spike + k] = 100.0f * c;
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
    std::printf("[denoise confidence dip] frame %d: surfaces %.5f..%.5f (expected %.5f)\n", k,
                r.lo, r.hi, expected[k]);
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

// NaN and Inf in the input (a broken integrator) never reach the output, nor the history; nor
// does a finite value too large to square (1e30), among noise or alone among black pixels (the
// all-black history's unclamped moments). The test sees the output; the moments' history stays
// finite by construction (kDenoiseMaxMomentLuminance).
TEST_F(DenoiseGpuTest, NonFiniteInputNeverReachesOutput) {
  const float bad[3] = {std::numeric_limits<float>::quiet_NaN(),
                        std::numeric_limits<float>::infinity(), 1.0e30f};
  for (const char* stabilize : {"0", "0.7"}) {
    SCOPED_TRACE(std::string("stabilize ") + stabilize);
    {
      Run run = make_run({{"stabilize", stabilize}});
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
    Run run = make_run({{"stabilize", stabilize}});
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
        const bool interior = u.x >= 0.0f && u.y >= 0.0f && u.x <= kInW - 1.0f &&
                              u.y <= kInH - 1.0f;
        inside += interior;
        const float* p = &out.pixels[4 * (std::size_t{y} * w + x)];
        for (int c = 0; c < 3; ++c) {
          float& worst = interior ? worst_inside : worst_border;
          worst = std::max(worst, std::abs(p[c] - (interior ? ramp(u.x, u.y) : bilinear)));
        }
      }
    }
    std::printf("[upscale ramp] %ux%u from %ux%u: worst inside %.3g, at the borders %.3g\n", w,
                h, kInW, kInH, worst_inside, worst_border);
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
        EXPECT_EQ(exact, surfaces) << w << "x" << h << " frame " << f
                                   << ": motion must be the jitter step";
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
}  // namespace lantern
