// Host visibility (VisibilityBackend::Host, lighting/visibility/host_visibility.h): on a CPU
// Vulkan device the shadow rays of restir.shade and integrators.baseline are answered by Embree
// on the host between two submissions. The pass runs in two variants of its shader: "hostemit"
// shades every pixel as if its shadow ray got through and writes the ray (one HostShadowRay per
// pixel) into the frame's ray buffer; the graph's host pass `visibility.host` traces the records
// in place (the buffer is mapped: zero copy on lavapipe); "hostresolve" then rewrites only the
// pixels whose ray was blocked with what the pass writes for a blocked ray (the surface's own
// emission). HostShadowRay has Embree's RTCRay layout (rtcore_ray.h), so the host hands the
// mapped records to rtcOccluded1M as they are; Embree marks a blocked ray by setting tfar to
// -infinity and leaves `id` alone, which tells traced slots from empty ones.
#ifndef LANTERN_SHARED_HOST_VISIBILITY_H
#define LANTERN_SHARED_HOST_VISIBILITY_H

#include "shared/bvh.h"
#include "shared/lang.h"
#include "shared/scene.h"
#include "shared/scene_bindings.h"

LANTERN_BEGIN_SHARED

// One shadow-ray segment origin + t * direction, t in [tnear, tfar] (the one epsilon policy of
// shared/bvh.h: direction = target - origin, tnear = t_eps, tfar = 1 - t_eps). A slot without a
// ray (the pixel traced nothing, or its points see each other) has tnear > tfar, which Embree
// skips: it reads as visible. `id` tells the two apart (host_ray_traced).
struct HostShadowRay {
  vec4 origin;     // xyz, w = tnear
  vec4 direction;  // xyz, w = time (0)
  float tfar;      // set to -infinity by the host when something blocks the segment
  uint mask;       // ~0u: every geometry
  uint id;         // the slot, or kHostRayNone (Embree leaves it alone)
  uint flags;      // 0
};
LANTERN_STATIC_SIZE(HostShadowRay, 48);

// Bindings of the ray buffer in the two variants: after any pass's own resources (a pass
// declares at most 24: PASS_BINDING(0..23)).
LANTERN_CONST uint kHostRaysBinding = kPassBindingBase + 24u;

// HostShadowRay.id of a slot that holds no ray.
LANTERN_CONST uint kHostRayNone = 0xffffffffu;

// The record of a slot that traces nothing (visible).
LANTERN_FUNC HostShadowRay host_ray_none() {
  HostShadowRay r;
  r.origin = vec4(0.0f, 0.0f, 0.0f, 1.0f);
  r.direction = vec4(0.0f, 0.0f, 1.0f, 0.0f);
  r.tfar = 0.0f;
  r.mask = 0xffffffffu;
  r.id = kHostRayNone;
  r.flags = 0u;
  return r;
}

// The record of the shadow segment origin -> target under the one epsilon policy of shared/bvh.h
// (what vis_visible writes in the emit variant). Where the ends see each other or the segment is
// not finite, the record still names its slot (the pass asked, and the resolve variant stores
// the verdict as the other backends do) but stays inactive (tnear > tfar): Embree skips it and it
// reads as visible, as the other backends answer.
LANTERN_FUNC HostShadowRay host_ray_segment(vec3 origin, vec3 target, uint slot) {
  HostShadowRay r = host_ray_none();
  r.id = slot;
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

// Whether the pass asked this slot's shadow ray (traced, or inactive because its ends see each
// other).
LANTERN_FUNC bool host_ray_traced(HostShadowRay r) {
  return r.id != kHostRayNone;
}

// Whether the record holds a segment Embree traces (tnear <= tfar): false for a record without a
// ray and for an asked but degenerate one.
LANTERN_FUNC bool host_ray_active(HostShadowRay r) {
  return host_ray_traced(r) && r.origin.w <= r.tfar;
}

// The answer the host left in a record: false only where a blocker was found (a record without a
// ray is visible).
LANTERN_FUNC bool host_ray_visible(HostShadowRay r) {
  return !(r.tfar < 0.0f);
}

// One closest-hit ray and, once the host traced it, its hit: Embree's RTCRayHit layout (the ray,
// then RTCHit), so the host hands the mapped records to rtcIntersect1M as they are (the
// "closestemit" / "closestresolve" variants of restir.initial: its BSDF candidates). The emit
// variant writes only the ray, from origin along direction for t in [0, tmax] (units of
// direction; the caller offsets the origin off its surface, bvh_ray_origin, as for the BVH); the
// host resets every record's hit, traces, and names the hit as the compute BVH does (VisHit): `instance` (Embree's geomID) the
// scene instance index, or kNoInstance where the ray meets nothing, `primitive` the triangle of
// the instance's mesh, (u, v) the barycentrics of vertices 1 and 2, ray.tfar the hit distance.
struct HostClosestRay {
  HostShadowRay ray;
  float ng_x;         // Embree's geometric normal (unnormalised; not read)
  float ng_y;
  float ng_z;
  float u;            // barycentric of vertex 1
  float v;            // barycentric of vertex 2
  uint primitive;     // Embree's primID, then the triangle of the instance's mesh
  uint instance;      // Embree's geomID, then the scene instance index (kNoInstance: a miss)
  uint instance_id;   // Embree's instID[0] (the host's, before it names the hit)
};
LANTERN_STATIC_SIZE(HostClosestRay, 80);

// Binding of the closest-hit ray buffer in the two variants (beside kHostRaysBinding).
LANTERN_CONST uint kHostClosestRaysBinding = kPassBindingBase + 25u;

// The record of a slot that traces nothing (a miss).
LANTERN_FUNC HostClosestRay host_closest_none() {
  HostClosestRay r;
  r.ray = host_ray_none();
  r.ng_x = 0.0f;
  r.ng_y = 0.0f;
  r.ng_z = 0.0f;
  r.u = 0.0f;
  r.v = 0.0f;
  r.primitive = kNoInstance;
  r.instance = kNoInstance;
  r.instance_id = kNoInstance;
  return r;
}

// The record of the closest-hit ray origin + t direction, t in [0, tmax]; slot names it. A ray
// that is not finite, or tmax <= 0, stays inactive (tnear > tfar: Embree skips it) and reads as
// a miss, as the BVH answers it.
LANTERN_FUNC HostClosestRay host_closest_ray(vec3 origin, vec3 direction, float tmax, uint slot) {
  HostClosestRay r = host_closest_none();
  r.ray.id = slot;
  float finite_check = dot(origin, origin) + dot(direction, direction);
  // NaN fails the comparisons; an infinite or overflowing origin or direction the first.
  if (!(finite_check < 3.0e38f) || !(tmax > 0.0f) || !(tmax <= kBvhMiss)) return r;
  r.ray.origin = vec4(origin, 0.0f);
  r.ray.direction = vec4(direction, 0.0f);
  r.ray.tfar = tmax;
  return r;
}

// Whether the host found a hit for this record.
LANTERN_FUNC bool host_closest_found(HostClosestRay r) {
  return r.instance != kNoInstance;
}

LANTERN_END_SHARED

#endif
