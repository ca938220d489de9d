// A small harness for ReSTIR GPU tests: a FrameRenderer with a chosen integrator rendering
// caller-made snapshots (so a test can move an occluder, remove a light or cut the camera
// exactly when it wants) through the render graph into a HeadlessTarget, read back as linear
// radiance, optionally with the frame's G-buffer instance ids, motion vectors and emission read
// back (to judge reuse by geometry, and to tell emitters from lit surfaces). Plus helpers for
// levels written inline and for region statistics.
#pragma once

#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "engine/level/level_loader.h"
#include "engine/world/world.h"
#include "lighting/frame/frame_renderer.h"
#include "lighting/frame/frame_session.h"
#include "lighting/frame/gbuffer_readback.h"
#include "lighting/integrators/integrator_registry.h"
#include "lighting/restir/restir_integrator.h"
#include "runtime/gpu/gpu_timer.h"
#include "runtime/gpu/shader_library.h"
#include "runtime/graph/graph_executor.h"
#include "runtime/image/image.h"
#include "runtime/image/image_metrics.h"
#include "runtime/target/headless_target.h"
#include "tests/runtime/scratch_dir.h"

namespace lantern::test {

class RenderHarness {
 public:
  RenderHarness(runtime::Device& device, runtime::ShaderLibrary& shaders,
                std::shared_ptr<const Level> level,
                std::unique_ptr<lighting::Integrator> integrator, std::uint32_t width,
                std::uint32_t height, std::uint32_t seed = 1)
      : gbuffer_(device),
        renderer_(device, shaders, std::move(level), std::move(integrator), width, height, seed),
        target_(device, {.width = width, .height = height}),
        session_(device, target_, renderer_) {
    renderer_.warm_up();
  }

  // One frame (the frame session's passes); with `gbuffer`, its G-buffer comes back too (a
  // readback pass in the HDR hook, after the G-buffer is written).
  runtime::ImageRGBA32F render(const FrameSnapshot& snapshot,
                               lighting::GBufferTexels* gbuffer = nullptr) {
    lighting::FrameHooks hooks;
    if (gbuffer != nullptr) {
      hooks.hdr = [this](runtime::graph::RenderGraph& graph, runtime::graph::BufferHandle hdr) {
        gbuffer_.add(graph, renderer_.last_inputs().gbuffer, renderer_.width(), renderer_.height());
        return hdr;
      };
    }
    lighting::FrameTiming timing;
    if (!session_.render(snapshot, hooks, &timing)) {
      throw RuntimeError("harness: the headless target gave no frame");
    }
    if (gbuffer != nullptr) *gbuffer = gbuffer_.read();
    pass_ms_ = std::move(timing.passes);
    return target_.read_output();
  }

  lighting::FrameRenderer& renderer() { return renderer_; }
  // The running integrator; its settings through describe_settings / apply_settings.
  lighting::Integrator& integrator() { return renderer_.integrator(); }
  const std::vector<std::pair<std::string, double>>& pass_ms() const { return pass_ms_; }

 private:
  lighting::GBufferReadback gbuffer_;
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

// A level from JSON text (written to a file of this process's own and loaded like any level).
inline std::shared_ptr<const Level> level_from_json(const std::string& name,
                                                    const std::string& json) {
  const std::filesystem::path file = process_scratch_dir() / ("restir_" + name + ".json");
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
