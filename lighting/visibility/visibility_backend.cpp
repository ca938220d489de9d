// Backend names and the per-device choice (visibility_backend.h).
#include "lighting/visibility/visibility_backend.h"

#include <fmt/format.h>

#include "engine/core/error.h"
#include "runtime/core/device_info.h"

namespace lantern::lighting {

std::string_view visibility_backend_name(VisibilityBackend backend) {
  switch (backend) {
    case VisibilityBackend::RayQuery:
      return "rayquery";
    case VisibilityBackend::Host:
      return "host";
    case VisibilityBackend::Bvh:
      break;
  }
  return "bvh";
}

VisibilitySetting parse_visibility_setting(std::string_view value) {
  if (value == "auto") return VisibilitySetting::Auto;
  if (value == "bvh") return VisibilitySetting::Bvh;
  if (value == "rayquery") return VisibilitySetting::RayQuery;
  if (value == "host") return VisibilitySetting::Host;
  throw InputError(
      fmt::format("--set visibility={}: expected auto, bvh, rayquery or host", value));
}

std::string_view visibility_setting_name(VisibilitySetting setting) {
  switch (setting) {
    case VisibilitySetting::Auto:
      return "auto";
    case VisibilitySetting::Bvh:
      return "bvh";
    case VisibilitySetting::RayQuery:
      return "rayquery";
    case VisibilitySetting::Host:
      return "host";
  }
  return "?";
}

bool is_cpu_device(const runtime::DeviceInfo& device) { return device.type == "cpu"; }

namespace {

VisibilityChoice choose_backend(const runtime::DeviceInfo& device, VisibilitySetting setting) {
  switch (setting) {
    case VisibilitySetting::Bvh:
      return {VisibilityBackend::Bvh, "visibility=bvh"};
    case VisibilitySetting::RayQuery:
      if (!device.ray_query) {
        throw InputError(
            fmt::format("--set visibility=rayquery: device '{}' lacks VK_KHR_ray_query / "
                        "VK_KHR_acceleration_structure (see `lantern devices`); use bvh or auto",
                        device.name));
      }
      return {VisibilityBackend::RayQuery, "visibility=rayquery"};
    case VisibilitySetting::Host:
      return {VisibilityBackend::Host, "visibility=host"};
    case VisibilitySetting::Auto:
      break;
  }
  const bool hardware = device.type == "discrete" || device.type == "integrated";
  if (hardware && device.ray_query) {
    return {VisibilityBackend::RayQuery,
            fmt::format("auto: {} GPU with ray query (hardware traversal)", device.type)};
  }
  if (hardware) {
    return {VisibilityBackend::Bvh, fmt::format("auto: {} GPU without ray query", device.type)};
  }
  if (is_cpu_device(device)) {
    return {VisibilityBackend::Host,
            "auto: cpu device, where Embree on the host answers the shadow rays (a level with "
            "alpha-tested materials keeps the compute BVH)"};
  }
  return {VisibilityBackend::Bvh,
          fmt::format("auto: {} device, where the compute BVH outruns ray query", device.type)};
}

}  // namespace

VisibilityChoice choose_visibility(const runtime::DeviceInfo& device, VisibilitySetting setting) {
  VisibilityChoice choice = choose_backend(device, setting);
  choice.cpu_device = is_cpu_device(device);
  return choice;
}

}  // namespace lantern::lighting
