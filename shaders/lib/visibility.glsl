// The one visibility interface of every pass (baseline, ReSTIR, reference):
//   bool vis_trace_closest(vec3 origin, vec3 dir, float tmax, out VisHit hit)
//     Closest triangle hit on origin + t * dir for 0 < t < tmax (dir need not be normalised: t is
//     in units of dir; pass kVisInfinity for an unbounded ray). On a hit, `hit` holds the instance
//     index (into the scene's instance array, GpuInstance / BvhInstance order), the primitive
//     (the mesh's original triangle index), the barycentrics (u, v) of vertices 1 and 2 and t.
//     On a miss `hit` is zeroed with hit.t = tmax. The caller offsets secondary-ray origins off
//     their surface; a hit at exactly t = 0 is never reported.
//   bool vis_visible(vec3 origin, vec3 target)
//     Shadow ray (any hit): true when nothing blocks the open segment. Epsilon policy (one owner,
//     bvh_shadow_t_epsilon in shared/bvh.h): both ends are pulled in by bvh_position_epsilon
//     (max(1e-4 m, 4e-6 x largest |coordinate| of either end), ~32 ulps), so the
//     surface the ray leaves and the emitter it reaches never count as blockers; points closer
//     than two epsilons see each other. Pass surface points and light points as they are.
// Backend, chosen at compile time (lighting/visibility/visibility_backend.h maps a shader path to
// its variant; shaders/variants.cmake compiles both):
//   default                        compute-shader BVH (shaders/lib/bvh_traverse.glsl), BVH arrays
//                                  in rgba32ui texel buffers (storage buffers with
//                                  VIS_BVH_STORAGE_BUFFERS, for A/B measurements).
//   LANTERN_VISIBILITY_RAY_QUERY   GL_EXT_ray_query against the TLAS bound as "scene_tlas".
//   LANTERN_VISIBILITY_HOST_EMIT / _RESOLVE   the BVH for closest hits; shadow rays written to /
//                                  answered from the host's ray buffer (shared/host_visibility.h;
//                                  the "hostemit" / "hostresolve" variants of restir.shade and
//                                  integrators.baseline). vis_host_begin(slot) names the pixel's
//                                  slot (a no-op in the other backends).
//   LANTERN_VISIBILITY_HOST_CLOSEST_EMIT / _RESOLVE   closest hits written to / answered from the
//                                  host's closest-hit ray buffer (HostClosestRay; the
//                                  "closestemit" / "closestresolve" variants of restir.initial);
//                                  shadow rays on the BVH. vis_host_closest_begin(first, count)
//                                  names the invocation's slots (a no-op elsewhere).
// Bindings: set VIS_DESCRIPTOR_SET (default 0), bindings VIS_BINDING_BASE .. + 3 (default 0..3):
// the BVH uses four (header, nodes, triangles, instances), ray query one (scene_tlas at
// VIS_TLAS_BINDING, default the base; the scene's at kSceneTlas, shared/scene_bindings.h).
// Frame passes get them through lib/scene_buffers.glsl (SceneHandles binds them); the standalone
// visibility probes bind lighting::VisibilityScene (lighting/visibility/visibility_scene.h).
#ifndef LANTERN_LIB_VISIBILITY_GLSL
#define LANTERN_LIB_VISIBILITY_GLSL

#include "shared/bvh.h"

#ifndef VIS_DESCRIPTOR_SET
#define VIS_DESCRIPTOR_SET 0
#endif
#ifndef VIS_BINDING_BASE
#define VIS_BINDING_BASE 0
#endif
#ifndef VIS_TLAS_BINDING
#define VIS_TLAS_BINDING VIS_BINDING_BASE
#endif

// An unbounded ray's tmax.
const float kVisInfinity = kBvhMiss;

struct VisHit {
  uint instance;   // index into the scene's instance array
  uint primitive;  // original triangle index within the instance's mesh
  float u;         // barycentric of vertex 1
  float v;         // barycentric of vertex 2
  float t;         // hit distance in units of dir
};

#ifdef LANTERN_VISIBILITY_RAY_QUERY

#extension GL_EXT_ray_query : require

layout(set = VIS_DESCRIPTOR_SET, binding = VIS_TLAS_BINDING) uniform accelerationStructureEXT
    scene_tlas;

// A candidate (non-opaque: alpha-tested) triangle counts where its material is not cut out (the
// same test as the BVH's leaf hook, lib/scene_buffers.glsl's scene_alpha_accept).
void vis_confirm_alpha_candidate(rayQueryEXT query) {
  if (rayQueryGetIntersectionTypeEXT(query, false) != gl_RayQueryCandidateIntersectionTriangleEXT)
    return;
#ifdef LANTERN_SCENE_ALPHA_TEST
  vec2 b = rayQueryGetIntersectionBarycentricsEXT(query, false);
  if (!scene_alpha_accept(uint(rayQueryGetIntersectionInstanceCustomIndexEXT(query, false)),
                          uint(rayQueryGetIntersectionPrimitiveIndexEXT(query, false)), b.x, b.y))
    return;
#endif
  rayQueryConfirmIntersectionEXT(query);
}

bool vis_trace_closest(vec3 origin, vec3 dir, float tmax, out VisHit hit) {
  hit = VisHit(0u, 0u, 0.0, 0.0, tmax);
  // NaN/infinite rays miss, as in the BVH backend (ray query leaves them undefined).
  float finite_check = dot(origin, origin) + dot(dir, dir);
  if (isnan(finite_check) || isinf(finite_check) || !(tmax > 0.0)) return false;
  rayQueryEXT query;
  // Opaque geometry commits itself; alpha-tested instances (TLAS FORCE_NO_OPAQUE) stop the loop
  // at each candidate, confirmed where the material is not cut out.
  rayQueryInitializeEXT(query, scene_tlas, gl_RayFlagsNoneEXT, 0xFF, origin, 0.0, dir,
                        min(tmax, kVisInfinity));
  while (rayQueryProceedEXT(query)) {
    vis_confirm_alpha_candidate(query);
  }
  if (rayQueryGetIntersectionTypeEXT(query, true) != gl_RayQueryCommittedIntersectionTriangleEXT)
    return false;
  // The TLAS instance custom index is the scene instance index (ray_query_scene.cpp).
  hit.instance = uint(rayQueryGetIntersectionInstanceCustomIndexEXT(query, true));
  hit.primitive = uint(rayQueryGetIntersectionPrimitiveIndexEXT(query, true));
  vec2 bary = rayQueryGetIntersectionBarycentricsEXT(query, true);
  hit.u = bary.x;
  hit.v = bary.y;
  hit.t = rayQueryGetIntersectionTEXT(query, true);
  return true;
}

bool vis_visible(vec3 origin, vec3 target) {
  float t_epsilon = bvh_shadow_t_epsilon(origin, target);
  if (t_epsilon < 0.0) return true;
  vec3 dir = target - origin;
  float finite_check = dot(origin, origin) + dot(dir, dir);
  if (isnan(finite_check) || isinf(finite_check)) return true;
  rayQueryEXT query;
  rayQueryInitializeEXT(query, scene_tlas, gl_RayFlagsTerminateOnFirstHitEXT, 0xFF, origin,
                        t_epsilon, dir, 1.0 - t_epsilon);
  while (rayQueryProceedEXT(query)) {
    vis_confirm_alpha_candidate(query);
  }
  return rayQueryGetIntersectionTypeEXT(query, true) == gl_RayQueryCommittedIntersectionNoneEXT;
}

void vis_host_begin(uint slot) {}
void vis_host_closest_begin(uint first, uint count) {}

#else  // compute-shader BVH

#define BVH_DESCRIPTOR_SET VIS_DESCRIPTOR_SET
#define BVH_BINDING_BASE VIS_BINDING_BASE
// Nodes, triangles and instances are fetched from rgba32ui texel buffers: 1.7x faster primary
// rays and 1.2-1.4x faster shadow rays than storage buffers on lavapipe (tests/visibility/
// visibility_bench, night_market). VIS_BVH_STORAGE_BUFFERS selects storage buffers (A/B).
#ifndef VIS_BVH_STORAGE_BUFFERS
#define BVH_TEXEL_BUFFERS
#endif
#include "lib/bvh_traverse.glsl"

#if defined(LANTERN_VISIBILITY_HOST_CLOSEST_EMIT) || \
    defined(LANTERN_VISIBILITY_HOST_CLOSEST_RESOLVE)

// Host closest hits (shared/host_visibility.h's HostClosestRay): a pass calls
// vis_host_closest_begin(first, count) once per invocation, before any vis_trace_closest, and
// then asks at most `count` closest-hit rays, which take slots first, first + 1, ... in the order
// asked; the emit variant ends with vis_host_closest_end(). Both variants must ask the same rays
// in the same order (the resolve reads slot k as the answer to the k-th ray the emit wrote).
#include "shared/host_visibility.h"

layout(std430, binding = kHostClosestRaysBinding) buffer HostClosestRays {
  HostClosestRay r[];
} host_closest_rays;

uint vis_closest_slot = 0u;
uint vis_closest_end = 0u;

#ifdef LANTERN_VISIBILITY_HOST_CLOSEST_EMIT
// Emit: vis_trace_closest records the ray and answers "miss" (the pass keeps nothing it computes
// from that); vis_host_closest_end writes the slots left unasked without a ray. Each slot's ray
// is written once, and only the ray: the host resets the hit before it traces (48 of the 80
// bytes: restir.initial_rays 3.57 -> 3.11 ms on night_market 320x180).
void vis_host_closest_begin(uint first, uint count) {
  vis_closest_slot = first;
  vis_closest_end = first + count;
}

bool vis_trace_closest(vec3 origin, vec3 dir, float tmax, out VisHit hit) {
  hit = VisHit(0u, 0u, 0.0, 0.0, tmax);
  host_closest_rays.r[vis_closest_slot].ray =
      host_closest_ray(origin, dir, tmax, vis_closest_slot).ray;
  ++vis_closest_slot;
  return false;
}

void vis_host_closest_end() {
  for (uint k = vis_closest_slot; k < vis_closest_end; ++k)
    host_closest_rays.r[k].ray = host_closest_none().ray;
}
#else
// Resolve: the host's hit for the invocation's next slot.
void vis_host_closest_begin(uint first, uint count) { vis_closest_slot = first; }

bool vis_trace_closest(vec3 origin, vec3 dir, float tmax, out VisHit hit) {
  HostClosestRay r = host_closest_rays.r[vis_closest_slot];
  ++vis_closest_slot;
  bool found = host_closest_found(r);
  hit = VisHit(found ? r.instance : 0u, found ? r.primitive : 0u, found ? r.u : 0.0,
               found ? r.v : 0.0, found ? r.ray.tfar : tmax);
  return found;
}
#endif

#else
void vis_host_closest_begin(uint first, uint count) {}

bool vis_trace_closest(vec3 origin, vec3 dir, float tmax, out VisHit hit) {
  BvhHit h;
  bool found = bvh_trace_closest(bvh_make_ray(origin, dir, 0.0, tmax), h);
  hit = VisHit(found ? h.instance : 0u, found ? h.primitive : 0u, found ? h.u : 0.0,
               found ? h.v : 0.0, h.t);
  return found;
}
#endif

#if defined(LANTERN_VISIBILITY_HOST_EMIT) || defined(LANTERN_VISIBILITY_HOST_RESOLVE)

// Host visibility (shared/host_visibility.h): closest-hit rays stay on the BVH above; shadow
// rays go through the frame's ray buffer. A pass calls vis_host_begin(slot) once per invocation
// before any vis_visible, and then asks at most one shadow ray (restir.shade, baseline).
#include "shared/host_visibility.h"

layout(std430, binding = kHostRaysBinding) buffer HostRays {
  HostShadowRay r[];
} host_rays;

uint vis_host_slot = 0u;

#ifdef LANTERN_VISIBILITY_HOST_EMIT
// Emit: the slot starts without a ray; vis_visible records the segment and answers "visible",
// so the pass writes what it shows where the ray gets through (the resolve variant rewrites the
// pixels whose ray was blocked).
void vis_host_begin(uint slot) {
  vis_host_slot = slot;
  host_rays.r[slot] = host_ray_none();
}

bool vis_visible(vec3 origin, vec3 target) {
  host_rays.r[vis_host_slot] = host_ray_segment(origin, target, vis_host_slot);
  return true;
}
#else
// Resolve: the host's answer for this invocation's slot.
void vis_host_begin(uint slot) { vis_host_slot = slot; }

bool vis_visible(vec3 origin, vec3 target) {
  return host_ray_visible(host_rays.r[vis_host_slot]);
}
#endif

#else
void vis_host_begin(uint slot) {}

bool vis_visible(vec3 origin, vec3 target) {
  return bvh_visible(origin, target);
}
#endif

#endif

#endif
