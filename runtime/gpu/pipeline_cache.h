// The VkPipelineCache, persisted between runs in $LANTERN_CACHE_DIR, $XDG_CACHE_HOME/lantern or
// ~/.cache/lantern as pipelines-<vendor>-<device>-<pipelineCacheUUID>.bin. The file's header is
// checked against the device before use; saving writes a temp file then renames it (atomic).
#pragma once

#include <vulkan/vulkan.h>

#include <cstddef>
#include <filesystem>

namespace lantern::runtime {

class PipelineCache {
 public:
  // `dir` empty: default_dir(). `persist` false: an in-memory cache that never touches disk.
  PipelineCache(VkDevice device, const VkPhysicalDeviceProperties& properties,
                const std::filesystem::path& dir, bool persist);
  ~PipelineCache();
  PipelineCache(const PipelineCache&) = delete;
  PipelineCache& operator=(const PipelineCache&) = delete;

  VkPipelineCache handle() const { return cache_; }
  const std::filesystem::path& file() const { return file_; }
  // Bytes of cache data accepted from disk at creation (0: none, or rejected).
  std::size_t loaded_bytes() const { return loaded_bytes_; }
  // Writes the current cache data; returns the number of bytes written (0 when not persistent).
  // I/O failures are logged as warnings: a missing cache only costs time.
  std::size_t save() const;

  static std::filesystem::path default_dir();

 private:
  VkDevice device_;
  VkPipelineCache cache_ = VK_NULL_HANDLE;
  std::filesystem::path file_;
  std::size_t loaded_bytes_ = 0;
};

}  // namespace lantern::runtime
