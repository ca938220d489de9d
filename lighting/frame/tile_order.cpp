// Shuffled tile dispatch (tile_order.h).
#include "lighting/frame/tile_order.h"

#include <algorithm>
#include <cstdlib>
#include <numeric>
#include <thread>

#include <sched.h>

#include "shared/pixel_groups.h"

namespace lantern::lighting {

std::uint32_t tile_count(std::uint32_t width, std::uint32_t height, std::uint32_t tile_size) {
  return ((width + tile_size - 1) / tile_size) * ((height + tile_size - 1) / tile_size);
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

runtime::SpecConstants pixel_group_constants(bool cpu_device) {
  runtime::SpecConstants constants;
  constants.set_id(gpu::kPixelGroupWidthId,
                   cpu_device ? gpu::kPixelGroupCpuWidth : gpu::kPixelGroupGpuSide);
  constants.set_id(gpu::kPixelGroupHeightId, cpu_device ? 1u : gpu::kPixelGroupGpuSide);
  return constants;
}

}  // namespace lantern::lighting
