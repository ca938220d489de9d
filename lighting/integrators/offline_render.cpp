// render_offline: World + FrameRenderer + HeadlessTarget through the render graph
// (offline_render.h).
#include "lighting/integrators/offline_render.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>

#include "engine/core/error.h"
#include "engine/world/world.h"
#include "lighting/frame/frame_renderer.h"
#include "runtime/core/device.h"
#include "runtime/gpu/gpu_timer.h"
#include "runtime/graph/graph_executor.h"
#include "runtime/graph/render_graph.h"
#include "runtime/target/headless_target.h"

namespace lantern::lighting {
namespace {

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

// Passes that deliver the image rather than render it.
bool is_delivery_pass(const std::string& name) {
  return name == "frame.output" || name.rfind("target.", 0) == 0;
}

// A frozen frame: the same poses again, no motion since the previous frame, history kept.
FrameSnapshot frozen_copy(const FrameSnapshot& s) {
  FrameSnapshot f = s;
  f.camera_cut = false;
  f.prev_camera = f.camera;
  for (SnapshotInstance& i : f.instances) i.prev_object_to_world = i.object_to_world;
  return f;
}

}  // namespace

double OfflineRenderResult::median_frame_ms() const {
  return median(frame_ms);
}

double OfflineRenderResult::median_pass_ms(const std::string& name) const {
  std::vector<double> values;
  for (const auto& frame : pass_ms) {
    double sum = 0.0;
    bool found = false;
    for (const auto& [pass, ms] : frame) {
      if (pass == name) {
        sum += ms;
        found = true;
      }
    }
    if (found) values.push_back(sum);
  }
  return median(values);
}

OfflineRenderResult render_offline(runtime::Device& device, runtime::ShaderLibrary& shaders,
                                   const Level& level, const OfflineRenderRequest& request) {
  return render_offline(device, shaders, std::make_shared<const Level>(level), request);
}

OfflineRenderResult render_offline(runtime::Device& device, runtime::ShaderLibrary& shaders,
                                   std::shared_ptr<const Level> level,
                                   const OfflineRenderRequest& request) {
  using Clock = std::chrono::steady_clock;
  if (request.width == 0 || request.height == 0 || request.frames == 0) {
    throw InputError(fmt::format("render size {}x{} and frame count {} must be positive",
                                 request.width, request.height, request.frames));
  }
  std::unique_ptr<Integrator> integrator = make_integrator(device, shaders, request.integrator);
  World world(level,
              {.threads = 1,
               .seed = request.seed,
               .fixed_dt = 1.0 / 60.0,
               .aspect = static_cast<float>(request.width) / static_cast<float>(request.height)});
  FrameRenderer renderer(device, shaders, level, std::move(integrator), request.width,
                         request.height, request.seed);
  renderer.warm_up();
  runtime::HeadlessTarget target(device, {.width = request.width, .height = request.height});
  runtime::graph::RenderGraph graph;
  runtime::graph::GraphExecutor executor(device);
  runtime::GpuTimer timer(device, 256);

  for (std::uint32_t k = 0; k < request.first_frame; ++k) world.step();
  if (request.first_frame > 0) world.request_camera_cut();

  OfflineRenderResult result;
  const std::size_t pixel_count = std::size_t{request.width} * request.height;
  std::vector<double> sum;  // mean in double precision
  if (request.average) sum.assign(pixel_count * 4, 0.0);
  std::shared_ptr<const FrameSnapshot> snapshot;
  for (std::uint32_t frame = 0; frame < request.frames; ++frame) {
    const auto start = Clock::now();
    if (request.animate || frame == 0) {
      world.step();
      snapshot = world.latest();
    } else if (frame == 1) {
      snapshot = std::make_shared<const FrameSnapshot>(frozen_copy(*snapshot));
    }
    const auto target_frame = target.begin_frame();
    if (!target_frame) throw RuntimeError("render: the headless target gave no frame");
    timer.reset(target_frame->cmd);
    graph.begin_frame();
    const runtime::graph::BufferHandle hdr = renderer.add_frame(graph, *snapshot);
    result.scene_update_ms.push_back(renderer.scene().last_update().cpu_ms);
    result.scene_updates.push_back(renderer.scene().last_update());
    const runtime::graph::ImageHandle output =
        renderer.add_output_pass(graph, hdr, target.import_output(graph, *target_frame), 0.0f);
    target.add_delivery(graph, *target_frame, output);
    graph.bake(executor.compile_options());
    executor.record(graph, target_frame->cmd, &timer);
    graph.end_frame();
    target.end_frame(*target_frame);
    result.frame_wall_ms.push_back(
        std::chrono::duration<double, std::milli>(Clock::now() - start).count());

    std::vector<std::pair<std::string, double>> passes;
    double gpu_ms = 0.0;
    for (const runtime::GpuTimer::Result& r : timer.resolve()) {
      if (r.depth != 0) continue;
      passes.emplace_back(r.name, r.ms);
      if (!is_delivery_pass(r.name)) gpu_ms += r.ms;
    }
    result.frame_ms.push_back(gpu_ms);
    result.pass_ms.push_back(std::move(passes));

    runtime::ImageRGBA32F image = target.read_output();
    if (request.average) {
      for (std::size_t i = 0; i < sum.size(); ++i) sum[i] += image.pixels[i];
    } else {
      result.images.push_back(std::move(image));
    }
  }
  if (request.average) {
    runtime::ImageRGBA32F image(request.width, request.height);
    for (std::size_t i = 0; i < sum.size(); ++i) {
      image.pixels[i] = static_cast<float>(sum[i] / request.frames);
    }
    result.images.push_back(std::move(image));
  }
  return result;
}

}  // namespace lantern::lighting
