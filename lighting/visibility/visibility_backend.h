// Which visibility backend a pass's shader runs (shaders/lib/visibility.glsl): the compute-shader
// BVH (any Vulkan 1.2 device; the fast path on lavapipe, shared/PLATFORM.md) or VK_KHR_ray_query
// (the fast path on real GPUs; a cross-check here). A pass loads its shader through
// visibility_variant() so it stays backend-agnostic:
//   shaders.load("restir/restir_initial.comp", visibility_variant(scene.backend()))
// and binds the scene's visibility data with VisibilityScene::bind (visibility_scene.h).
#pragma once

#include <string_view>

namespace lantern::runtime {
struct DeviceCaps;
}

namespace lantern::lighting {

enum class VisibilityBackend { Bvh, RayQuery };

// The shader variant compiled for the backend (shaders/variants.cmake): "" for the BVH (the
// default build of every shader), "rayquery" with LANTERN_VISIBILITY_RAY_QUERY defined.
constexpr std::string_view visibility_variant(VisibilityBackend backend) {
  return backend == VisibilityBackend::RayQuery ? "rayquery" : "";
}

// "bvh" / "rayquery" (for logs, benchmark output and the --set visibility=... value).
std::string_view visibility_backend_name(VisibilityBackend backend);

// The backend to use on a device: the BVH unless ray query is requested. Requesting ray query on a
// device without it throws lantern::InputError naming the device capability.
VisibilityBackend choose_visibility_backend(const runtime::DeviceCaps& caps, bool want_ray_query);

}  // namespace lantern::lighting
