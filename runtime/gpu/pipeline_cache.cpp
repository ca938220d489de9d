// On-disk pipeline cache.
#include "runtime/gpu/pipeline_cache.h"

#include <fmt/format.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <vector>

#include "engine/core/log.h"
#include "runtime/core/vk_check.h"

namespace lantern::runtime {
namespace {

std::vector<char> read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return {};
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The header every driver writes (VkPipelineCacheHeaderVersionOne); data for another device or
// driver version is dropped here rather than trusting every driver to reject it.
bool header_matches(const std::vector<char>& data, const VkPhysicalDeviceProperties& p) {
  VkPipelineCacheHeaderVersionOne header{};
  if (data.size() < sizeof(header)) return false;
  std::memcpy(&header, data.data(), sizeof(header));
  return header.headerSize >= sizeof(header) &&
         header.headerVersion == VK_PIPELINE_CACHE_HEADER_VERSION_ONE &&
         header.vendorID == p.vendorID && header.deviceID == p.deviceID &&
         std::memcmp(header.pipelineCacheUUID, p.pipelineCacheUUID, VK_UUID_SIZE) == 0;
}

}  // namespace

std::filesystem::path PipelineCache::default_dir() {
  if (const char* dir = std::getenv("LANTERN_CACHE_DIR"); dir != nullptr && *dir != '\0')
    return dir;
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg != nullptr && *xdg != '\0')
    return std::filesystem::path(xdg) / "lantern";
  if (const char* home = std::getenv("HOME"); home != nullptr && *home != '\0')
    return std::filesystem::path(home) / ".cache" / "lantern";
  return std::filesystem::temp_directory_path() / "lantern-cache";
}

PipelineCache::PipelineCache(VkDevice device, const VkPhysicalDeviceProperties& properties,
                             const std::filesystem::path& dir, bool persist)
    : device_(device) {
  std::vector<char> data;
  if (persist) {
    std::string uuid;
    for (std::uint8_t byte : properties.pipelineCacheUUID) uuid += fmt::format("{:02x}", byte);
    file_ = (dir.empty() ? default_dir() : dir) / fmt::format("pipelines-{:04x}-{:04x}-{}.bin",
                                                              properties.vendorID,
                                                              properties.deviceID, uuid);
    data = read_file(file_);
    if (!data.empty() && !header_matches(data, properties)) {
      log::info("pipeline cache {} does not match this device and driver (or is damaged): ignored",
                file_.string());
      data.clear();
    }
  }
  VkPipelineCacheCreateInfo info{VK_STRUCTURE_TYPE_PIPELINE_CACHE_CREATE_INFO};
  info.initialDataSize = data.size();
  info.pInitialData = data.empty() ? nullptr : data.data();
  VK_CHECK(vkCreatePipelineCache(device_, &info, nullptr, &cache_));
  loaded_bytes_ = data.size();
}

PipelineCache::~PipelineCache() {
  vkDestroyPipelineCache(device_, cache_, nullptr);
}

std::size_t PipelineCache::save() const {
  if (file_.empty()) return 0;
  std::size_t size = 0;
  VK_CHECK(vkGetPipelineCacheData(device_, cache_, &size, nullptr));
  std::vector<char> data(size);
  VK_CHECK(vkGetPipelineCacheData(device_, cache_, &size, data.data()));
  data.resize(size);

  std::error_code ec;
  std::filesystem::create_directories(file_.parent_path(), ec);
  // Unique temp name per process, then rename: readers never see a half-written file.
  const std::filesystem::path temp = file_.string() + fmt::format(".tmp{}", ::getpid());
  {
    std::ofstream out(temp, std::ios::binary | std::ios::trunc);
    out.write(data.data(), static_cast<std::streamsize>(data.size()));
    if (!out) {
      log::warn("cannot write pipeline cache {}: {}", temp.string(), std::strerror(errno));
      std::filesystem::remove(temp, ec);
      return 0;
    }
  }
  std::filesystem::rename(temp, file_, ec);
  if (ec) {
    log::warn("cannot rename pipeline cache to {}: {}", file_.string(), ec.message());
    std::filesystem::remove(temp, ec);
    return 0;
  }
  return data.size();
}

}  // namespace lantern::runtime
