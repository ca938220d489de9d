// render_offline: build and upload the scene, warm the pipeline up, run and read back N frames.
#include "lighting/integrators/offline_render.h"

#include <fmt/format.h>

#include <algorithm>

#include "engine/core/error.h"
#include "engine/core/log.h"
#include "lighting/integrators/baseline_integrator.h"
#include "lighting/scene/frame_constants.h"
#include "lighting/scene/gpu_scene.h"
#include "lighting/scene/scene_data.h"
#include "runtime/core/device.h"
#include "runtime/gpu/gpu_timer.h"
#include "runtime/gpu/transfer.h"

namespace lantern::lighting {

IntegratorKind parse_integrator(std::string_view name) {
  if (name == "baseline") return IntegratorKind::Baseline;
  if (name == "reference") return IntegratorKind::Reference;
  if (name == "restir") return IntegratorKind::Restir;
  throw InputError(
      fmt::format("unknown integrator '{}' (expected restir, baseline or reference)", name));
}

const char* integrator_name(IntegratorKind kind) {
  switch (kind) {
    case IntegratorKind::Baseline:
      return "baseline";
    case IntegratorKind::Reference:
      return "reference";
    case IntegratorKind::Restir:
      return "restir";
  }
  return "?";
}

void require_implemented(IntegratorKind kind) {
  if (kind != IntegratorKind::Baseline) {
    throw InputError(fmt::format("integrator '{}' is not implemented yet (use baseline)",
                                 integrator_name(kind)));
  }
}

double OfflineRenderResult::median_frame_ms() const {
  if (frame_ms.empty()) return 0.0;
  std::vector<double> sorted = frame_ms;
  std::sort(sorted.begin(), sorted.end());
  const std::size_t n = sorted.size();
  return n % 2 == 1 ? sorted[n / 2] : 0.5 * (sorted[n / 2 - 1] + sorted[n / 2]);
}

OfflineRenderResult render_offline(runtime::Device& device, runtime::ShaderLibrary& shaders,
                                   const Level& level, const OfflineRenderRequest& request) {
  require_implemented(request.integrator);
  if (request.width == 0 || request.height == 0 || request.frames == 0) {
    throw InputError(fmt::format("render size {}x{} and frame count {} must be positive",
                                 request.width, request.height, request.frames));
  }

  const SceneData scene = build_scene_data(level);
  const GpuScene gpu_scene(device, scene);
  log::debug("scene: {} instances, {} BVH triangles, {} lights ({} emissive triangles), {:.1f} MiB",
            scene.instances.size(), scene.bvh.triangles().size(), scene.lights.lights().size(),
            scene.emissive_triangles, static_cast<double>(gpu_scene.bytes()) / (1024.0 * 1024.0));

  BaselineIntegrator baseline(device, shaders);
  baseline.warm_up();

  const FrameCounts counts{gpu_scene.light_count(), gpu_scene.instance_count(),
                           scene.emissive_triangles};
  const gpu::FrameConstants constants =
      make_frame_constants(level.camera, request.width, request.height, 0, request.seed, counts);
  runtime::Buffer constants_buffer(device, {.size = sizeof(gpu::FrameConstants),
                                            .usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                            .memory = runtime::MemoryUsage::DeviceLocal,
                                            .name = "frame.constants"});
  runtime::upload_buffer(device, constants_buffer,
                         std::span<const gpu::FrameConstants>(&constants, 1));
  const std::size_t pixel_count = std::size_t{request.width} * request.height;
  runtime::Buffer radiance(device, {.size = pixel_count * 4 * sizeof(float),
                                    .usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                    .memory = runtime::MemoryUsage::DeviceLocal,
                                    .name = "integrators.baseline.radiance"});

  OfflineRenderResult result;
  runtime::GpuTimer timer(device);
  std::vector<double> sum;  // mean in double precision
  if (request.average) sum.assign(pixel_count * 4, 0.0);
  for (std::uint32_t frame = 0; frame < request.frames; ++frame) {
    device.submit_and_wait([&](VkCommandBuffer cmd) {
      timer.reset(cmd);
      auto scope = timer.scope(cmd, "integrators.baseline");
      baseline.record(cmd, gpu_scene, constants_buffer, radiance, request.width, request.height,
                      frame);
    });
    result.frame_ms.push_back(timer.resolve().at(0).ms);
    std::vector<float> pixels = runtime::read_buffer<float>(device, radiance);
    if (request.average) {
      for (std::size_t i = 0; i < sum.size(); ++i) sum[i] += pixels[i];
    } else {
      runtime::ImageRGBA32F image(request.width, request.height);
      image.pixels = std::move(pixels);
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
