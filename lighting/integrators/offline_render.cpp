// render_offline: frames of a HeadlessSession, read back (offline_render.h).
#include "lighting/integrators/offline_render.h"

#include <fmt/format.h>

#include <span>

#include "engine/core/error.h"
#include "engine/perf/statistics.h"
#include "engine/world/world.h"
#include "lighting/frame/frame_renderer.h"
#include "lighting/frame/headless_session.h"
#include "runtime/image/image_metrics.h"

namespace lantern::lighting {
namespace {

double median(const std::vector<double>& values) {
  return perf::percentile(std::span<const double>(values), 50.0);
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
  if (request.width == 0 || request.height == 0 || request.frames == 0) {
    throw InputError(fmt::format("render size {}x{} and frame count {} must be positive",
                                 request.width, request.height, request.frames));
  }
  HeadlessSession session(device, shaders, std::move(level),
                          {.integrator = request.integrator,
                           .width = request.width,
                           .height = request.height,
                           .seed = request.seed,
                           .world_seed = request.world_seed,
                           .output = request.output,
                           .render_scale = request.render_scale});
  session.warm_up();
  session.skip(request.first_frame);

  OfflineRenderResult result;
  runtime::ImageAccumulator mean;
  std::shared_ptr<const FrameSnapshot> snapshot;
  runtime::ImageRGBA32F image;
  for (std::uint32_t frame = 0; frame < request.frames; ++frame) {
    const bool step = request.animate || frame == 0;
    if (step) {
      session.step_world();
      snapshot = session.world().latest();
    } else if (frame == 1) {
      snapshot = std::make_shared<const FrameSnapshot>(frozen(*snapshot));
    }
    FrameTiming timing = session.render(*snapshot, &image);
    result.scene_update_ms.push_back(timing.scene_update_ms);
    result.scene_updates.push_back(session.renderer().scene().last_update());
    result.frame_wall_ms.push_back(timing.wall_ms + (step ? timing.step_ms : 0.0));
    result.frame_ms.push_back(timing.gpu_ms);
    result.pass_ms.push_back(std::move(timing.passes));
    if (request.average) {
      mean.add(image);
    } else {
      result.images.push_back(std::move(image));
    }
  }
  if (request.average) {
    result.images.push_back(mean.mean());
    if (mean.count() >= 2) result.standard_error = mean.standard_error();
  }
  return result;
}

}  // namespace lantern::lighting
