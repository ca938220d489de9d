// G-buffer benchmark (not a test): GPU milliseconds of the `gbuffer` raster pass (and of
// `gbuffer.draws`) per level and size, median over N frames after warm-up, from the render
// graph's GPU timestamps (min alongside: the machine is shared and noisy), and the wall time of
// the whole submitted frame. The level's own camera; no read-back inside the timed frames.
// Usage: gbuffer_bench [--frames N] [level ...]   (default: cornell_lights night_market, 15 frames)
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <string>
#include <vector>

#include "engine/level/level_loader.h"
#include "lighting/scene/frame_constants.h"
#include "lighting/scene/scene_data.h"
#include "runtime/core/device.h"
#include "runtime/gpu/shader_library.h"
#include "tests/gbuffer/gbuffer_harness.h"

namespace {

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace

int main(int argc, char** argv) {
  using namespace lantern;
  int frames = 15;
  std::vector<std::string> levels;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--frames" && i + 1 < argc) {
      frames = std::max(1, std::atoi(argv[++i]));
    } else {
      levels.push_back(arg);
    }
  }
  if (levels.empty()) levels = {"cornell_lights", "night_market"};

  runtime::Device device{runtime::DeviceOptions{}};
  runtime::ShaderLibrary shaders;
  fmt::print("device: {}\n", device.info().name);
  fmt::print("{:<16} {:>9} {:>10} {:>10} {:>12} {:>10} {:>12} {:>12} {:>7}\n", "level", "size",
             "triangles", "instances", "gbuffer ms", "(min)", "draws ms", "frame wall", "frames");
  for (const std::string& name : levels) {
    const Level level = load_level_argument(name);
    const lighting::SceneData scene = lighting::build_scene_data(level);
    std::size_t triangles = 0;
    for (const gpu::GpuInstance& inst : scene.instances) triangles += inst.geometry.z / 3;
    test::GBufferHarness harness(device, shaders, scene);
    harness.warm_up();
    for (const auto& [w, h] : {std::pair{320u, 180u}, std::pair{640u, 360u}}) {
      const gpu::FrameConstants fc = lighting::make_frame_constants(level.camera, w, h, 0, 1, {});
      harness.render(fc, false);  // first frame: transient allocation
      std::vector<double> raster, draws, wall;
      for (int f = 0; f < frames; ++f) {
        const auto start = std::chrono::steady_clock::now();
        harness.render(fc, false);
        wall.push_back(
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                .count());
        raster.push_back(harness.last_ms("gbuffer"));
        draws.push_back(harness.last_ms("gbuffer.draws"));
      }
      fmt::print("{:<16} {:>9} {:>10} {:>10} {:>12.3f} {:>10.3f} {:>12.3f} {:>12.3f} {:>7}\n", name,
                 fmt::format("{}x{}", w, h), triangles, scene.instances.size(), median(raster),
                 *std::min_element(raster.begin(), raster.end()), median(draws), median(wall),
                 frames);
    }
  }
  return 0;
}
