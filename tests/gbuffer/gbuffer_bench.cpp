// G-buffer benchmark (not a test): GPU milliseconds of the G-buffer passes (`gbuffer.draws`,
// `gbuffer.cull`, `gbuffer`, the host method's host pass `gbuffer.host`, `gbuffer.resolve` and
// their total) per level, size and method, median over N frames
// after warm-up, from the render graph's GPU timestamps (min alongside: the machine is shared and
// noisy), and the wall time of the whole submitted frame. Methods are interleaved frame by frame
// (A/B in one run), and each method's total is also given as the median of its per-round ratio to
// the first method's total (robust to load changes during the run). The level's own camera; no
// read-back inside the timed frames.
// Usage: gbuffer_bench [--frames N] [--methods auto,visibility,forward,host] [level ...]
//        (default: cornell_lights night_market, 15 frames, forward and visibility)
//        A level suffixed ":untextured" is the level with every material texture and alpha mode
//        removed (the same geometry without the textured path: the cost of textures, A/B).
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "engine/core/error.h"
#include "engine/level/level_loader.h"
#include "lighting/scene/frame_constants.h"
#include "lighting/scene/scene_data.h"
#include "runtime/core/device.h"
#include "runtime/gpu/shader_library.h"
#include "tests/gbuffer/gbuffer_harness.h"

namespace {

using lantern::lighting::GBufferMethod;

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

GBufferMethod parse_method(const std::string& name) {
  try {
    return lantern::lighting::parse_gbuffer_method(name);
  } catch (const lantern::InputError& e) {
    fmt::print(stderr, "gbuffer_bench: {}\n", e.what());
    std::exit(2);
  }
}

}  // namespace

int main(int argc, char** argv) {
  using namespace lantern;
  int frames = 15;
  std::vector<std::string> levels;
  std::vector<GBufferMethod> methods = {GBufferMethod::Forward, GBufferMethod::Visibility};
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--frames" && i + 1 < argc) {
      frames = std::max(1, std::atoi(argv[++i]));
    } else if (arg == "--methods" && i + 1 < argc) {
      methods.clear();
      std::stringstream list(argv[++i]);
      for (std::string name; std::getline(list, name, ',');) methods.push_back(parse_method(name));
    } else {
      levels.push_back(arg);
    }
  }
  if (levels.empty()) levels = {"cornell_lights", "night_market"};
  if (methods.empty()) methods = {GBufferMethod::Visibility};

  runtime::Device device{runtime::DeviceOptions{}};
  runtime::ShaderLibrary shaders;
  fmt::print("device: {}\n", device.info().name);
  fmt::print(
      "{:<15} {:>8} {:>9} {:>5} {:<11} {:>9} {:>8} {:>7} {:>7} {:>8} {:>7} {:>8} {:>7} {:>8} "
      "{:>5}\n",
      "level", "size", "triangles", "inst", "method", "total ms", "(min)", "draws", "cull",
      "gbuffer", "host", "resolve", "ratio", "wall ms", "frames");
  for (const std::string& name : levels) {
    const bool untextured = name.size() > 11 && name.ends_with(":untextured");
    Level level = load_level_argument(untextured ? name.substr(0, name.size() - 11) : name);
    if (untextured) {
      for (Material& m : level.materials) {
        m.base_color_texture = m.metallic_roughness_texture = m.normal_texture =
            m.emissive_texture = TextureRef{};
        m.alpha_mode = AlphaMode::Opaque;
      }
    }
    const lighting::SceneData scene = lighting::build_scene_data(level);
    std::size_t triangles = 0;
    for (const gpu::GpuInstance& inst : scene.instances) triangles += inst.geometry.z / 3;
    std::vector<std::unique_ptr<test::GBufferHarness>> harnesses;
    for (GBufferMethod method : methods) {
      harnesses.push_back(std::make_unique<test::GBufferHarness>(
          device, shaders, scene, lighting::GBufferPassOptions{.method = method}));
      harnesses.back()->warm_up();
    }
    for (const auto& [w, h] : {std::pair{320u, 180u}, std::pair{640u, 360u}}) {
      const gpu::FrameConstants fc = lighting::make_frame_constants(level.camera, w, h, 0, 1, {});
      struct Samples {
        std::vector<double> total, draws, cull, raster, host, resolve, wall, ratio;
      };
      std::vector<Samples> samples(methods.size());
      for (auto& harness : harnesses) harness->render(fc, false);  // transient allocation
      for (int f = 0; f < frames; ++f) {
        for (std::size_t m = 0; m < methods.size(); ++m) {
          test::GBufferHarness& harness = *harnesses[m];
          const auto start = std::chrono::steady_clock::now();
          harness.render(fc, false);
          samples[m].wall.push_back(
              std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                  .count());
          const double draws = std::max(0.0, harness.last_ms("gbuffer.draws"));
          const double raster = std::max(0.0, harness.last_ms("gbuffer"));
          const double resolve = std::max(0.0, harness.last_ms("gbuffer.resolve"));
          const double cull = std::max(0.0, harness.last_ms("gbuffer.cull"));
          const double host = std::max(0.0, harness.last_ms("gbuffer.host"));
          samples[m].cull.push_back(cull);
          samples[m].host.push_back(host);
          samples[m].draws.push_back(draws);
          samples[m].raster.push_back(raster);
          samples[m].resolve.push_back(resolve);
          samples[m].total.push_back(draws + cull + raster + host + resolve);
        }
        for (std::size_t m = 0; m < methods.size(); ++m) {
          samples[m].ratio.push_back(samples[m].total.back() / samples[0].total.back());
        }
      }
      for (std::size_t m = 0; m < methods.size(); ++m) {
        const Samples& s = samples[m];
        fmt::print(
            "{:<15} {:>8} {:>9} {:>5} {:<11} {:>9.3f} {:>8.3f} {:>7.3f} {:>7.3f} {:>8.3f} "
            "{:>7.3f} {:>8.3f} {:>7.3f} {:>8.3f} {:>5}\n",
            name, fmt::format("{}x{}", w, h), triangles, scene.instances.size(),
            lighting::gbuffer_method_name(methods[m]), median(s.total),
            *std::min_element(s.total.begin(), s.total.end()), median(s.draws), median(s.cull),
            median(s.raster), median(s.host), median(s.resolve), median(s.ratio), median(s.wall),
            frames);
      }
    }
  }
  return 0;
}
