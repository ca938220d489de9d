// Which visibility backend a pass's shader runs (shaders/lib/visibility.glsl): the compute-shader
// BVH (any Vulkan 1.2 device; the fast path on lavapipe, shared/PLATFORM.md) or VK_KHR_ray_query
// (the fast path on real GPUs, whose traversal is in hardware). The frame picks one from the
// `visibility` setting (`--set visibility=auto|bvh|rayquery`) and the device, once:
// make_integrator loads each tracing pass's shader through visibility_variant(backend), and
// GpuScene builds the TLAS that variant traces (bound through SceneHandles as scene_tlas).
//   shaders.load("restir/restir_initial.comp", visibility_variant(backend))
#pragma once

#include <string>
#include <string_view>

namespace lantern::runtime {
struct DeviceInfo;
}

namespace lantern::lighting {

// Host: on a CPU device (lavapipe) the one shadow ray per pixel of restir.shade and
// integrators.baseline is traced by Embree on the host in the graph pass visibility.host
// (lighting/visibility/host_visibility.h); every other ray stays on the compute BVH.
enum class VisibilityBackend { Bvh, RayQuery, Host };

// The `visibility` setting: a backend, or auto (pick by device).
enum class VisibilitySetting { Auto, Bvh, RayQuery, Host };

// The shader variant compiled for the backend (shaders/variants.cmake): "" for the BVH (the
// default build of every shader, and what the host backend's other passes run), "rayquery" with
// LANTERN_VISIBILITY_RAY_QUERY defined. The host backend's split passes load "hostemit" and
// "hostresolve" themselves.
constexpr std::string_view visibility_variant(VisibilityBackend backend) {
  return backend == VisibilityBackend::RayQuery ? "rayquery" : "";
}

// "bvh" / "rayquery" / "host" (for logs, `lantern info`, benchmark output and the setting's
// values).
std::string_view visibility_backend_name(VisibilityBackend backend);

// "auto" | "bvh" | "rayquery" | "host"; lantern::InputError naming the value otherwise (checked before any
// device work).
VisibilitySetting parse_visibility_setting(std::string_view value);
std::string_view visibility_setting_name(VisibilitySetting setting);

// Whether `device` runs on the CPU (lavapipe): where the host backends (Embree answering shadow
// rays, the host G-buffer) are the fast path.
bool is_cpu_device(const runtime::DeviceInfo& device);

struct VisibilityChoice {
  VisibilityBackend backend = VisibilityBackend::Bvh;
  std::string why;  // one line: the setting and, for auto, the device fact that decided
  bool cpu_device = false;  // the device is a CPU (lavapipe): the host G-buffer is a fast path
};

// The backend for `setting` on `device` (pure: tests pass a hand-made DeviceInfo). auto: ray query
// on a discrete or integrated GPU that has it (hardware traversal), host on a CPU device
// (lavapipe: Embree on the same cores traces the shadow rays many times faster than the compute
// BVH, whose traversal lavapipe runs one lane per ray; its ray query is 0.5x the BVH), else the
// BVH. rayquery on a device without
// VK_KHR_ray_query: lantern::InputError naming the device.
VisibilityChoice choose_visibility(const runtime::DeviceInfo& device, VisibilitySetting setting);

}  // namespace lantern::lighting
