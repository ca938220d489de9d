// Shuffled tile dispatch (tile_order.h).
#include "lighting/frame/tile_order.h"

#include <algorithm>
#include <cstdlib>
#include <numeric>
#include <thread>

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
  unsigned threads = std::thread::hardware_concurrency();
  if (const char* forced = std::getenv("LP_NUM_THREADS"); forced != nullptr && *forced != '\0') {
    threads = static_cast<unsigned>(std::strtoul(forced, nullptr, 10));
  }
  return std::clamp(threads, 1u, 64u);
}

}  // namespace lantern::lighting
