// Shuffled tile dispatch (tile_order.h).
#include "lighting/frame/tile_order.h"

#include <algorithm>
#include <cstdlib>
#include <numeric>
#include <thread>

#include <sched.h>

#include "lighting/visibility/visibility_backend.h"
#include "runtime/core/device.h"
#include "shared/pixel_groups.h"

namespace lantern::lighting {

std::uint32_t tile_count(std::uint32_t width, std::uint32_t height, glm::uvec2 tile) {
  return ((width + tile.x - 1) / tile.x) * ((height + tile.y - 1) / tile.y);
}

std::uint32_t tile_count(std::uint32_t width, std::uint32_t height,
                         const runtime::ComputePipeline& pipeline) {
  return tile_count(width, height, {pipeline.local_size()[0], pipeline.local_size()[1]});
}

std::uint32_t tile_stride(std::uint32_t count) {
  if (count < 3 || count > 65535) return 1;
  auto stride = static_cast<std::uint32_t>(static_cast<double>(count) * 0.6180339887);
  while (std::gcd(stride, count) != 1) ++stride;
  return stride;
}

std::uint32_t tile_bands(bool cpu_device) {
  if (!cpu_device) return 0;
  // As llvmpipe counts its threads: the CPUs this process may run on, LP_NUM_THREADS instead
  // when it is a whole number (any base strtol reads; anything else is ignored), at most 32
  // (LP_MAX_THREADS); 0 threads runs a dispatch on one.
  long threads = static_cast<long>(std::thread::hardware_concurrency());
  cpu_set_t affinity;
  if (sched_getaffinity(0, sizeof(affinity), &affinity) == 0) threads = CPU_COUNT(&affinity);
  if (const char* forced = std::getenv("LP_NUM_THREADS"); forced != nullptr && *forced != '\0') {
    char* end = nullptr;
    const long value = std::strtol(forced, &end, 0);
    if (end != nullptr && *end == '\0') threads = value;
  }
  return static_cast<std::uint32_t>(std::clamp(threads, 1L, 32L));
}

glm::uvec2 pixel_group_shape(bool cpu_device) {
  return cpu_device ? glm::uvec2(gpu::kPixelGroupCpuWidth, 1u)
                    : glm::uvec2(gpu::kPixelGroupGpuSide, gpu::kPixelGroupGpuSide);
}

runtime::SpecConstants pixel_group_constants(glm::uvec2 shape) {
  runtime::SpecConstants constants;
  constants.set_id(gpu::kPixelGroupWidthId, shape.x);
  constants.set_id(gpu::kPixelGroupHeightId, shape.y);
  return constants;
}

runtime::SpecConstants pixel_group_constants(const runtime::Device& device) {
  return pixel_group_constants(pixel_group_shape(is_cpu_device(device.info())));
}

}  // namespace lantern::lighting
