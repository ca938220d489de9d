#include "runtime/core/vk_check.h"

#include <fmt/format.h>

#include <filesystem>

#include "engine/core/error.h"

namespace lantern::runtime {

std::string_view vk_result_name(VkResult r) {
  switch (r) {
#define LANTERN_CASE(x) \
  case x:               \
    return #x
    LANTERN_CASE(VK_SUCCESS);
    LANTERN_CASE(VK_NOT_READY);
    LANTERN_CASE(VK_TIMEOUT);
    LANTERN_CASE(VK_INCOMPLETE);
    LANTERN_CASE(VK_SUBOPTIMAL_KHR);
    LANTERN_CASE(VK_ERROR_OUT_OF_HOST_MEMORY);
    LANTERN_CASE(VK_ERROR_OUT_OF_DEVICE_MEMORY);
    LANTERN_CASE(VK_ERROR_INITIALIZATION_FAILED);
    LANTERN_CASE(VK_ERROR_DEVICE_LOST);
    LANTERN_CASE(VK_ERROR_MEMORY_MAP_FAILED);
    LANTERN_CASE(VK_ERROR_LAYER_NOT_PRESENT);
    LANTERN_CASE(VK_ERROR_EXTENSION_NOT_PRESENT);
    LANTERN_CASE(VK_ERROR_FEATURE_NOT_PRESENT);
    LANTERN_CASE(VK_ERROR_INCOMPATIBLE_DRIVER);
    LANTERN_CASE(VK_ERROR_TOO_MANY_OBJECTS);
    LANTERN_CASE(VK_ERROR_FORMAT_NOT_SUPPORTED);
    LANTERN_CASE(VK_ERROR_FRAGMENTED_POOL);
    LANTERN_CASE(VK_ERROR_OUT_OF_POOL_MEMORY);
    LANTERN_CASE(VK_ERROR_SURFACE_LOST_KHR);
    LANTERN_CASE(VK_ERROR_NATIVE_WINDOW_IN_USE_KHR);
    LANTERN_CASE(VK_ERROR_OUT_OF_DATE_KHR);
    LANTERN_CASE(VK_ERROR_VALIDATION_FAILED_EXT);
#undef LANTERN_CASE
    default:
      return "VK_RESULT_UNKNOWN";
  }
}

void vk_fail(VkResult result, const char* call, const char* file, int line) {
  throw RuntimeError(fmt::format("{} failed: {} ({}) at {}:{}", call, vk_result_name(result),
                                 static_cast<int>(result),
                                 std::filesystem::path(file).filename().string(), line));
}

}  // namespace lantern::runtime
