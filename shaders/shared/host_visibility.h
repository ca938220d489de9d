// Host visibility (VisibilityBackend::Host, lighting/visibility/host_visibility.h): on a CPU
// Vulkan device the shadow rays of restir.shade and integrators.baseline are answered by Embree
// on the host between two submissions. The pass runs twice: its "hostemit" variant writes one
// HostShadowRay per pixel into the frame's ray buffer, the graph's host pass `visibility.host`
// traces them in place (the buffer is mapped: zero copy on lavapipe), and the "hostresolve"
// variant reads each pixel's answer where the pass asks vis_visible (shaders/lib/visibility.glsl).
// HostShadowRay has Embree's RTCRay layout (rtcore_ray.h), so the host hands the mapped records
// to rtcOccluded1M as they are; Embree marks a blocked ray by setting tfar to -infinity.
#ifndef LANTERN_SHARED_HOST_VISIBILITY_H
#define LANTERN_SHARED_HOST_VISIBILITY_H

#include "shared/bvh.h"
#include "shared/lang.h"
#include "shared/scene_bindings.h"

LANTERN_BEGIN_SHARED

// One shadow-ray segment origin + t * direction, t in [tnear, tfar] (the one epsilon policy of
// shared/bvh.h: direction = target - origin, tnear = t_eps, tfar = 1 - t_eps). A slot without a
// ray (the pixel traced nothing, or its points see each other) has tnear > tfar, which Embree
// skips: it reads as visible.
struct HostShadowRay {
  vec4 origin;     // xyz, w = tnear
  vec4 direction;  // xyz, w = time (0)
  float tfar;      // set to -infinity by the host when something blocks the segment
  uint mask;       // ~0u: every geometry
  uint id;         // the slot (unused by Embree's occlusion query)
  uint flags;      // 0
};
LANTERN_STATIC_SIZE(HostShadowRay, 48);

// Bindings of the ray buffer in the two variants: after any pass's own resources.
LANTERN_CONST uint kHostRaysBinding = kPassBindingBase + 16u;

// The record of a slot that traces nothing (visible).
LANTERN_FUNC HostShadowRay host_ray_none(uint slot) {
  HostShadowRay r;
  r.origin = vec4(0.0f, 0.0f, 0.0f, 1.0f);
  r.direction = vec4(0.0f, 0.0f, 1.0f, 0.0f);
  r.tfar = 0.0f;
  r.mask = 0xffffffffu;
  r.id = slot;
  r.flags = 0u;
  return r;
}

// The record of the shadow segment origin -> target under the one epsilon policy of shared/bvh.h
// (what vis_visible writes in the emit variant), or none (visible) where the ends see each other
// or the segment is not finite, as the other backends answer.
LANTERN_FUNC HostShadowRay host_ray_segment(vec3 origin, vec3 target, uint slot) {
  HostShadowRay r = host_ray_none(slot);
  float t_epsilon = bvh_shadow_t_epsilon(origin, target);
  vec3 direction = target - origin;
  float finite_check = dot(origin, origin) + dot(direction, direction);
  // NaN fails both comparisons; an infinite or overflowing length fails the second.
  if (!(t_epsilon >= 0.0f) || !(finite_check < 3.0e38f)) return r;
  r.origin = vec4(origin, t_epsilon);
  r.direction = vec4(direction, 0.0f);
  r.tfar = 1.0f - t_epsilon;
  return r;
}

// The answer the host left in a record: false only where a blocker was found.
LANTERN_FUNC bool host_ray_visible(float tfar) {
  return !(tfar < 0.0f);
}

LANTERN_END_SHARED

#endif
