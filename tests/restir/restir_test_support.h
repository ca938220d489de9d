// A small harness for ReSTIR GPU tests: a FrameRenderer with a chosen integrator rendering
// caller-made snapshots (so a test can move an occluder, remove a light or cut the camera
// exactly when it wants) through the render graph into a HeadlessTarget, read back as linear
// radiance, optionally with the frame's G-buffer instance ids, motion vectors and emission read
// back (to judge reuse by geometry, and to tell emitters from lit surfaces). Plus helpers for
// levels written inline and for region statistics.
#pragma once

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "engine/level/level_loader.h"
#include "engine/world/world.h"
#include "lighting/frame/frame_renderer.h"
#include "lighting/frame/frame_session.h"
#include "lighting/integrators/integrator_registry.h"
#include "lighting/restir/restir_integrator.h"
#include "runtime/gpu/buffer.h"
#include "runtime/gpu/gpu_timer.h"
#include "runtime/gpu/shader_library.h"
#include "runtime/graph/graph_executor.h"
#include "runtime/image/image.h"
#include "runtime/image/image_metrics.h"
#include "runtime/target/headless_target.h"

namespace lantern::test {

// Host copies of one frame's gbuffer.ids, gbuffer.motion and gbuffer.emission_metallic
// (shared/gbuffer.h), row-major from the top-left.
struct GBufferReadback {
  std::vector<glm::uvec4> ids;      // x: instance (gpu::kNoInstance = sky)
  std::vector<glm::vec4> motion;    // xy: previous pixel position minus current
  std::vector<glm::vec4> emission;  // rgb: emitted radiance of the surface seen; a: metallic
};

class RenderHarness {
 public:
  RenderHarness(runtime::Device& device, runtime::ShaderLibrary& shaders,
                std::shared_ptr<const Level> level,
                std::unique_ptr<lighting::Integrator> integrator, std::uint32_t width,
                std::uint32_t height, std::uint32_t seed = 1)
      : device_(device),
        renderer_(device, shaders, std::move(level), std::move(integrator), width, height, seed),
        target_(device, {.width = width, .height = height}),
        session_(device, target_, renderer_) {
    renderer_.warm_up();
  }

  // One frame (the frame session's passes); with `gbuffer`, its ids, motion and emission images
  // come back too (a readback pass in the HDR hook, after the G-buffer is written).
  runtime::ImageRGBA32F render(const FrameSnapshot& snapshot, GBufferReadback* gbuffer = nullptr) {
    lighting::FrameHooks hooks;
    if (gbuffer != nullptr) {
      hooks.hdr = [this](runtime::graph::RenderGraph&, runtime::graph::BufferHandle hdr) {
        add_gbuffer_readback();
        return hdr;
      };
    }
    lighting::FrameTiming timing;
    if (!session_.render(snapshot, hooks, &timing)) {
      throw RuntimeError("harness: the headless target gave no frame");
    }
    if (gbuffer != nullptr) {
      const std::size_t n = std::size_t{renderer_.width()} * renderer_.height();
      gbuffer->ids.resize(n);
      gbuffer->motion.resize(n);
      gbuffer->emission.resize(n);
      std::memcpy(gbuffer->ids.data(), readback_[0].mapped(), n * sizeof(glm::uvec4));
      std::memcpy(gbuffer->motion.data(), readback_[1].mapped(), n * sizeof(glm::vec4));
      std::memcpy(gbuffer->emission.data(), readback_[2].mapped(), n * sizeof(glm::vec4));
    }
    pass_ms_ = std::move(timing.passes);
    return target_.read_output();
  }

  lighting::FrameRenderer& renderer() { return renderer_; }
  // The running integrator; its settings through describe_settings / apply_settings.
  lighting::Integrator& integrator() { return renderer_.integrator(); }
  const std::vector<std::pair<std::string, double>>& pass_ms() const { return pass_ms_; }

 private:
  // A Transfer pass copying gbuffer.ids, .motion and .emission_metallic (16 bytes a texel each)
  // into host-visible buffers.
  void add_gbuffer_readback() {
    const std::size_t bytes = std::size_t{renderer_.width()} * renderer_.height() * 16;
    if (readback_.empty()) {
      for (const char* name :
           {"test.ids_readback", "test.motion_readback", "test.emission_readback"}) {
        readback_.emplace_back(device_, runtime::BufferDesc{
                                            .size = bytes,
                                            .usage = VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                            .memory = runtime::MemoryUsage::Readback,
                                            .name = name});
      }
    }
    const lighting::GBufferHandles& g = renderer_.last_inputs().gbuffer;
    struct Copy {
      runtime::graph::ImageHandle images[kImages];
      runtime::graph::BufferHandle buffers[kImages];
    };
    const std::uint32_t width = renderer_.width(), height = renderer_.height();
    runtime::graph::RenderGraph& graph = session_.graph();
    graph.add_pass<Copy>(
        "test.gbuffer_readback", runtime::graph::PassKind::Transfer,
        [&](runtime::graph::PassBuilder& b, Copy& d) {
          runtime::graph::ImportInfo host_read;
          host_read.final = runtime::graph::AccessState{
              VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT, VK_IMAGE_LAYOUT_UNDEFINED};
          d.images[0] = g.ids;
          d.images[1] = g.motion;
          d.images[2] = g.emission_metallic;
          for (int i = 0; i < kImages; ++i) {
            b.read(d.images[i], runtime::graph::Access::TransferSrc);
            d.buffers[i] = b.write(graph.import_buffer(readback_[i].name(), readback_[i].handle(),
                                                        {readback_[i].size()}, host_read),
                                   runtime::graph::Access::TransferDst);
          }
          b.side_effect();
        },
        [width, height](runtime::graph::PassContext& ctx, const Copy& d) {
          for (int i = 0; i < kImages; ++i) {
            VkBufferImageCopy region{};
            region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
            region.imageExtent = {width, height, 1};
            vkCmdCopyImageToBuffer(ctx.cmd(), ctx.image(d.images[i]),
                                   VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, ctx.buffer(d.buffers[i]),
                                   1, &region);
          }
        });
  }

  static constexpr int kImages = 3;  // ids, motion, emission_metallic
  runtime::Device& device_;
  std::vector<runtime::Buffer> readback_;
  lighting::FrameRenderer renderer_;
  runtime::HeadlessTarget target_;
  lighting::FrameSession session_;
  std::vector<std::pair<std::string, double>> pass_ms_;
};

inline std::unique_ptr<lighting::Integrator> make_restir(
    runtime::Device& device, runtime::ShaderLibrary& shaders,
    std::vector<std::pair<std::string, std::string>> settings, std::string preset = "balanced") {
  return lighting::make_integrator(
      device, shaders,
      {.name = "restir", .preset = std::move(preset), .settings = std::move(settings)});
}

inline std::unique_ptr<lighting::Integrator> make_baseline(runtime::Device& device,
                                                           runtime::ShaderLibrary& shaders) {
  return lighting::make_integrator(device, shaders, {.name = "baseline"});
}

// A level from JSON text (written to a temporary file and loaded like any level).
inline std::shared_ptr<const Level> level_from_json(const std::string& name,
                                                    const std::string& json) {
  const std::filesystem::path file =
      std::filesystem::temp_directory_path() / ("lantern_restir_" + name + ".json");
  std::ofstream(file) << json;
  return std::make_shared<const Level>(load_level(file));
}

inline FrameSnapshot first_snapshot(std::shared_ptr<const Level> level, std::uint32_t width,
                                    std::uint32_t height) {
  World world(level, {.threads = 1,
                      .seed = 1,
                      .fixed_dt = 1.0 / 60.0,
                      .aspect = static_cast<float>(width) / static_cast<float>(height)});
  return world.step();
}

inline bool all_finite(const runtime::ImageRGBA32F& image) {
  for (float v : image.pixels)
    if (!std::isfinite(v)) return false;
  return true;
}

// Mean of RGB over the pixels where mask != 0.
inline double masked_mean(const runtime::ImageRGBA32F& image, const std::vector<std::uint8_t>& mask) {
  double sum = 0.0;
  std::size_t n = 0;
  for (std::size_t p = 0; p < mask.size(); ++p) {
    if (!mask[p]) continue;
    sum += image.pixels[4 * p] + image.pixels[4 * p + 1] + image.pixels[4 * p + 2];
    n += 3;
  }
  return n ? sum / static_cast<double>(n) : 0.0;
}

inline std::size_t count(const std::vector<std::uint8_t>& mask) {
  std::size_t n = 0;
  for (std::uint8_t m : mask) n += m ? 1 : 0;
  return n;
}

}  // namespace lantern::test
