// Backend names and the per-device choice (visibility_backend.h).
#include "lighting/visibility/visibility_backend.h"

#include <fmt/format.h>

#include "engine/core/error.h"
#include "runtime/core/device_features.h"

namespace lantern::lighting {

std::string_view visibility_backend_name(VisibilityBackend backend) {
  return backend == VisibilityBackend::RayQuery ? "rayquery" : "bvh";
}

VisibilityBackend choose_visibility_backend(const runtime::DeviceCaps& caps, bool want_ray_query) {
  if (!want_ray_query) return VisibilityBackend::Bvh;
  if (!caps.ray_query)
    throw InputError(
        "visibility backend 'rayquery' needs VK_KHR_ray_query and VK_KHR_acceleration_structure, "
        "which this device lacks (see `lantern devices`); use 'bvh'");
  return VisibilityBackend::RayQuery;
}

}  // namespace lantern::lighting
