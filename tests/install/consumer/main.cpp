// Embeds the lighting module from the installed package: renders one 32x18 baseline frame of
// cornell_lights (read from the package's content) with the package's SPIR-V, headless, with
// validation on. Exits 1 unless validation ran without error, every pixel is finite and the frame
// is not black.
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <glm/glm.hpp>
#include <memory>

#include "engine/level/level_loader.h"
#include "lighting/frame/headless_session.h"
#include "runtime/core/device.h"
#include "runtime/gpu/shader_library.h"
#include "runtime/image/image.h"
#include "shared/color.h"

namespace {

int render_one_frame() {
  using namespace lantern;
  runtime::DeviceOptions device_options;
  device_options.validation = true;
  device_options.persist_pipeline_cache = false;
  runtime::Device device(device_options);
  runtime::ShaderLibrary shaders(CONSUMER_SHADER_DIR);
  const auto level = std::make_shared<const Level>(
      load_level(std::filesystem::path(CONSUMER_CONTENT_DIR) / "levels/cornell_lights.json"));

  lighting::SessionOptions options;
  options.integrator.name = "baseline";
  options.width = 32;
  options.height = 18;
  lighting::HeadlessSession session(device, shaders, level, options);
  session.warm_up();
  runtime::ImageRGBA32F image;
  session.render(session.step_world(), &image);

  double sum = 0.0;
  for (std::uint32_t y = 0; y < image.height; ++y)
    for (std::uint32_t x = 0; x < image.width; ++x) {
      const float* p = image.at(x, y);
      sum += gpu::luminance(glm::vec3(p[0], p[1], p[2]));
    }
  const double mean = sum / (double(image.width) * image.height);
  const std::size_t non_finite = image.count_non_finite();
  std::printf("lantern_consumer: %ux%u baseline frame of %s, mean luminance %g, %zu non-finite, "
              "shaders from %s\n",
              image.width, image.height, level->name.c_str(), mean, non_finite,
              shaders.dir().c_str());
  if (!device.validation_enabled()) {
    std::fprintf(stderr, "lantern_consumer: validation layer unavailable\n");
    return 1;
  }
  if (device.validation_errors() != 0) {
    std::fprintf(stderr, "lantern_consumer: %u validation errors\n", device.validation_errors());
    return 1;
  }
  if (image.width != options.width || image.height != options.height) {
    std::fprintf(stderr, "lantern_consumer: read back %ux%u, rendered %ux%u\n", image.width,
                 image.height, options.width, options.height);
    return 1;
  }
  if (non_finite != 0 || !std::isfinite(mean) || !(mean > 0.0)) {
    std::fprintf(stderr, "lantern_consumer: the frame is not finite and lit\n");
    return 1;
  }
  return 0;
}

}  // namespace

int main() {
  try {
    return render_one_frame();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "lantern_consumer: %s\n", e.what());
    return 1;
  }
}
