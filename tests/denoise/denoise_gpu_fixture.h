// The denoiser's GPU tests' fixture (denoise_*_test.cpp, upscale_gpu_test.cpp: one executable):
// the denoise.* chain end to end on lavapipe through FrameRenderer (output Denoised), fed images
// the test chooses by a test integrator (ImageIntegrator: copies a host image into the HDR
// buffer), over the real G-buffer of a small grey scene (kScene), and the images the tests build.
// The fixture checks validation ran clean.
#pragma once

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

namespace lantern::denoise_test {

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
  std::vector<std::pair<std::string, std::string>> describe_settings() const override { return {}; }
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
inline constexpr const char* kScene = R"({
  "materials": { "grey": { "base_color": [0.5, 0.5, 0.5], "roughness": 0.8 } },
  "primitives": [
    { "type": "plane", "name": "floor", "size": [6, 6], "material": "grey" },
    { "type": "plane", "name": "wall", "size": [6, 6], "material": "grey",
      "translation": [0, 0, -2], "rotation_deg": [90, 0, 0] },
    { "type": "box", "name": "box", "size": [0.8, 1.2, 0.8], "material": "grey",
      "translation": [0, 0.6, -0.5] } ],
  "lights": [ { "type": "point", "name": "lamp", "position": [0, 2, 1], "intensity": 1 } ],
  "camera": { "position": [0, 1.2, 3], "target": [0, 0.6, -1], "yfov_deg": 60 } })";

inline std::size_t instance_index(const Level& level, const std::string& name) {
  for (std::size_t i = 0; i < level.instances.size(); ++i)
    if (level.instances[i].name == name) return i;
  throw RuntimeError("denoise test scene has no " + name);
}

// Radiance c on every pixel (sky included).
inline ImageRGBA32F constant(float c, std::uint32_t w = kW, std::uint32_t h = kH) {
  ImageRGBA32F image(w, h);
  for (std::size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = i % 4 == 3 ? 1.0f : c;
  return image;
}

// c x u, u uniform in [0, 2) per pixel, channel and frame (mean c; a hash, reproducible).
inline ImageRGBA32F noisy(float c, std::uint32_t frame) {
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
inline std::vector<std::uint8_t> surfaces(const lighting::GBufferTexels& g) {
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
    run.harness =
        std::make_unique<RenderHarness>(device, shaders, level, std::move(integrator), w, h);
    run.harness->renderer().set_output(lighting::FrameOutput::Denoised);
    run.harness->renderer().set_denoise_settings(
        lighting::make_denoise_settings("balanced", denoise));
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
  // The G-buffer of the still scene's first frame (a probe run).
  lighting::GBufferTexels first_frame_gbuffer() {
    Run probe = make_run();
    lighting::GBufferTexels g;
    (void)render(probe, constant(0.0f), test::first_snapshot(level, kW, kH), &g);
    return g;
  }
  // An interior surface pixel of the still scene (interior_surface_pixel of a probe run's first
  // frame; 0 when there is none) and, in `mask`, its surface pixels.
  std::size_t interior_pixel(std::vector<std::uint8_t>& mask);
  // A pixel of the still scene's wall whose block of `left` / `right` columns and `up` / `down`
  // rows shows only the wall (first_block_of; 0 when there is none), and in `g` the first frame's
  // G-buffer.
  std::size_t wall_block(std::uint32_t left, std::uint32_t right, std::uint32_t up,
                         std::uint32_t down, lighting::GBufferTexels& g);
  // An image of c with a lone spike of factor x c at an interior surface pixel of the still
  // scene (`spike`; `mask`: the surface pixels).
  ImageRGBA32F lone_spike(float c, float factor, std::size_t& spike,
                          std::vector<std::uint8_t>& mask);
};

// A surface pixel whose 8 neighbours are surfaces too, the first from the image's centre on (0
// when there is none).
inline std::size_t interior_surface_pixel(const std::vector<std::uint8_t>& mask) {
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

// The first pixel, row by row from the image's middle row down and then from the top, whose block
// of `left` / `right` columns and `up` / `down` rows around it shows only instance `instance` (0
// when there is none).
inline std::size_t first_block_of(const lighting::GBufferTexels& g, std::uint32_t instance,
                                  std::uint32_t left, std::uint32_t right, std::uint32_t up,
                                  std::uint32_t down) {
  for (std::uint32_t row = 0; row < g.height; ++row) {
    const std::uint32_t y = (g.height / 2 + row) % g.height;
    if (y < up || y + down >= g.height) continue;
    for (std::uint32_t x = left; x + right < g.width; ++x) {
      bool inside = true;
      for (std::uint32_t by = y - up; by <= y + down && inside; ++by) {
        for (std::uint32_t bx = x - left; bx <= x + right && inside; ++bx) {
          inside = g.ids[g.index(bx, by)].x == instance;
        }
      }
      if (inside) return g.index(x, y);
    }
  }
  return 0;
}

inline std::size_t DenoiseGpuTest::interior_pixel(std::vector<std::uint8_t>& mask) {
  mask = surfaces(first_frame_gbuffer());
  return interior_surface_pixel(mask);
}

inline std::size_t DenoiseGpuTest::wall_block(std::uint32_t left, std::uint32_t right,
                                              std::uint32_t up, std::uint32_t down,
                                              lighting::GBufferTexels& g) {
  g = first_frame_gbuffer();
  const auto wall = static_cast<std::uint32_t>(instance_index(*level, "wall"));
  return first_block_of(g, wall, left, right, up, down);
}

inline ImageRGBA32F DenoiseGpuTest::lone_spike(float c, float factor, std::size_t& spike,
                                               std::vector<std::uint8_t>& mask) {
  spike = interior_pixel(mask);
  ImageRGBA32F input = constant(c);
  for (int k = 0; k < 3; ++k) input.pixels[4 * spike + k] = factor * c;
  return input;
}

// The lowest and highest red value over the masked pixels.
struct Range {
  float lo = std::numeric_limits<float>::infinity();
  float hi = -std::numeric_limits<float>::infinity();
};
inline Range masked_range(const ImageRGBA32F& image, const std::vector<std::uint8_t>& mask) {
  Range r;
  for (std::size_t p = 0; p < mask.size(); ++p) {
    if (!mask[p]) continue;
    r.lo = std::min(r.lo, image.pixels[4 * p]);
    r.hi = std::max(r.hi, image.pixels[4 * p]);
  }
  return r;
}

}  // namespace lantern::denoise_test
