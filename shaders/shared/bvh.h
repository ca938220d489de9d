// GPU layout of the scene BVH (nodes, triangles, instances, scene header) and the ray-box and
// ray-triangle tests that the CPU traversal and the GLSL traversal (shaders/lib/bvh_traverse.glsl)
// both run. Built on the CPU by lighting/bvh/.
#ifndef LANTERN_SHARED_BVH_H
#define LANTERN_SHARED_BVH_H

#include "shared/lang.h"

LANTERN_BEGIN_SHARED

// Node layout (32 bytes = two 16-byte fetches, so a texel buffer of rgba32ui serves it as well):
// nodes of one tree are flattened depth first; an interior node's left child is the next node and
// its right child is `index`. The traversal reads both children of a node together (two boxes),
// visits the nearer one first and pushes the other, so the common "descend left" step reads memory
// that follows the parent. A leaf holds `count` >= 1 consecutive primitives starting at `index`:
// triangles (BLAS, relative to the instance's triangle_offset) or one instance (TLAS). Child
// indices are relative to the tree's first node (BvhInstance::node_offset, tlas_node_offset).
// Boxes are padded outward by a few ulps (lighting/bvh/bvh_builder.cpp) so that rays lying in a
// box face, and hits on triangle edges, are never culled by the slab test.
// The w components carry uint bits (floatBitsToUint): GLSL must fetch nodes as uvec4 and bit-cast,
// never through a float format that could flush these small integers (denormals) to zero.
struct BvhNode {
  vec4 bounds_min;  // xyz = box min corner, w = bits of index (right child or first primitive)
  vec4 bounds_max;  // xyz = box max corner, w = bits of count (0 = interior node)
};
LANTERN_STATIC_SIZE(BvhNode, 32);

// A triangle stored for Möller–Trumbore: one vertex and the two edges leaving it (object space;
// world space in the merged tree of fixed instances, lighting/bvh/scene_bvh.h).
struct BvhTriangle {
  vec4 v0;  // xyz = vertex 0, w = bits of the mesh's original triangle index (the hit's primitive)
  vec4 e1;  // xyz = vertex 1 - vertex 0, w = bits of 0, or in the merged tree its instance + 1
  vec4 e2;  // xyz = vertex 2 - vertex 0, w = 0
};
LANTERN_STATIC_SIZE(BvhTriangle, 48);

// One placed mesh: the TLAS leaves point at these; the BLAS of the mesh starts at node_offset in
// the shared node array and its triangles at triangle_offset in the shared triangle array.
// BvhInstance.flags: the instance's material is alpha-tested, so a triangle hit counts only
// where bvh_accept_hit says so (shared/bvh_traverse.h; lib/bvh_traverse.glsl's reads the
// material's cutout through the scene buffers).
LANTERN_CONST uint kBvhInstanceAlphaTested = 1u;

struct BvhInstance {
  mat4 object_to_world;
  mat4 world_to_object;  // inverse of object_to_world: rays are moved into object space
  uint node_offset;
  uint triangle_offset;
  uint user_id;  // caller's id for the instance (e.g. ECS entity index), returned in hits
  uint flags;    // kBvhInstance* bits
};
LANTERN_STATIC_SIZE(BvhInstance, 144);

// Where the TLAS lives in the node array (after all BLAS nodes, so rebuilding it each frame leaves
// the BLAS nodes in place); tlas_node_count = 0 means an empty scene: every ray misses.
struct BvhSceneHeader {
  uint tlas_node_offset;
  uint tlas_node_count;
  uint instance_count;
  uint triangle_count;
};
LANTERN_STATIC_SIZE(BvhSceneHeader, 16);

// A ray segment: points origin + t * direction for t in [tmin, tmax]. direction need not be
// normalised (shadow rays use target - origin and tmax = 1).
struct BvhRay {
  vec4 origin;     // xyz = origin, w = tmin
  vec4 direction;  // xyz = direction, w = tmax
};
LANTERN_STATIC_SIZE(BvhRay, 32);

// Closest hit: origin + t * direction lies on triangle `primitive` (original index within its
// mesh) of instance `instance` (index into the instance array), at barycentrics (u, v) of
// vertices 1 and 2.
struct BvhHit {
  float t;
  float u;
  float v;
  uint instance;
  uint primitive;
  uint user_id;
  uint pad0;
  uint pad1;
};
LANTERN_STATIC_SIZE(BvhHit, 32);

// Binding slots of the BVH buffers, relative to the base binding a pass gives them
// (shaders/lib/bvh_traverse.glsl: BVH_DESCRIPTOR_SET, BVH_BINDING_BASE).
LANTERN_CONST uint kBvhBindingHeader = 0u;  // BvhSceneHeader (storage buffer)
LANTERN_CONST uint kBvhBindingNodes = 1u;   // BvhNode[] (storage buffer or rgba32ui texel buffer)
LANTERN_CONST uint kBvhBindingTriangles = 2u;  // BvhTriangle[] (same)
LANTERN_CONST uint kBvhBindingInstances = 3u;  // BvhInstance[] (same)
LANTERN_CONST uint kBvhBindingCount = 4u;

// Depth bound of every tree the builder emits (it switches to median splits deep down, so depth
// stays below this for any input that fits in memory); sizes the traversal stack.
LANTERN_CONST uint kBvhStackSize = 64u;
// A box test returns this when the ray misses the box.
LANTERN_CONST float kBvhMiss = 3.402823e38f;
// Direction components smaller than this are replaced by it (keeping the sign), so that 1/d is
// finite and a slab test never computes 0 * inf = NaN for a ray parallel to a slab.
// 1/kBvhMinDirection = 1e30 stays finite, and times the builder's box padding (>= 1e-20) still
// dwarfs any real ray distance.
LANTERN_CONST float kBvhMinDirection = 1e-30f;
// Conservative widening of the slab test's far distance (1 + 2 * gamma(3) of Ize, "Robust BVH Ray
// Traversal", JCGT 2013): float rounding can then never make a ray miss a box it touches.
LANTERN_CONST float kBvhBoxFarScale = 1.0000004f;
// Shadow rays start and end this far (relative to the scene's coordinate magnitude, at least this
// much in absolute units) from their end points to skip the surfaces they leave and arrive at.
LANTERN_CONST float kBvhShadowEpsilon = 1e-4f;

LANTERN_FUNC BvhRay bvh_make_ray(vec3 origin, vec3 direction, float tmin, float tmax) {
  BvhRay ray;
  ray.origin = vec4(origin, tmin);
  ray.direction = vec4(direction, tmax);
  return ray;
}

// Relative part of the shadow epsilon: 4e-6 of the largest coordinate magnitude is ~32 float
// ulps there, enough for the rounding of reconstructed hit points, and no longer grows to metres
// far from the origin (at 1e5 m the old 1e-4 * |p| was 10 m and erased every shadow).
LANTERN_CONST float kBvhShadowRelativeEpsilon = 4e-6f;

// World-space epsilon for points whose largest coordinate magnitude is `magnitude`.
LANTERN_FUNC float bvh_position_epsilon(float magnitude) {
  return max(kBvhShadowEpsilon, kBvhShadowRelativeEpsilon * magnitude);
}

// Origin of a ray leaving surface point p on the side of its geometric normal ng (unit): p pushed
// along ng by bvh_position_epsilon of p's largest coordinate, so the ray never hits the surface
// it starts on (closest-hit rays; shadow rays pull both ends in by bvh_shadow_t_epsilon instead).
LANTERN_FUNC vec3 bvh_ray_origin(vec3 p, vec3 ng) {
  vec3 magnitude = abs(p);
  return p + ng * bvh_position_epsilon(max(magnitude.x, max(magnitude.y, magnitude.z)));
}

// The shadow-ray segment between two points: origin + t * (target - origin) for t in
// [t_eps, 1 - t_eps], where t_eps * |target - origin| = bvh_position_epsilon(largest coordinate
// magnitude of either end), so neither the surface the ray leaves nor the one it reaches counts
// as a blocker. Returns t_eps, or -1 when the points are closer than two epsilons (then they see
// each other) or the distance is NaN.
LANTERN_FUNC float bvh_shadow_t_epsilon(vec3 origin, vec3 target) {
  vec3 direction = target - origin;
  float distance = length(direction);
  vec3 magnitude = max(abs(origin), abs(target));
  float epsilon = bvh_position_epsilon(max(magnitude.x, max(magnitude.y, magnitude.z)));
  if (!(distance > 2.0f * epsilon)) return -1.0f;
  return epsilon / distance;
}

LANTERN_FUNC bool bvh_node_is_leaf(BvhNode node) {
  return floatBitsToUint(node.bounds_max.w) != 0u;
}
LANTERN_FUNC uint bvh_node_index(BvhNode node) {
  return floatBitsToUint(node.bounds_min.w);
}
LANTERN_FUNC uint bvh_node_count(BvhNode node) {
  return floatBitsToUint(node.bounds_max.w);
}

// 1/direction with tiny components clamped to +-kBvhMinDirection: always finite, never NaN.
LANTERN_FUNC vec3 bvh_safe_reciprocal(vec3 d) {
  vec3 s = vec3(d.x < 0.0f ? -1.0f : 1.0f, d.y < 0.0f ? -1.0f : 1.0f, d.z < 0.0f ? -1.0f : 1.0f);
  return s / max(abs(d), vec3(kBvhMinDirection));
}

// Slab test: the ray parameter where the ray enters the box within [tmin, tmax], or kBvhMiss.
LANTERN_FUNC float bvh_ray_box(vec3 origin, vec3 inv_direction, float tmin, float tmax,
                               vec3 box_min, vec3 box_max) {
  vec3 t0 = (box_min - origin) * inv_direction;
  vec3 t1 = (box_max - origin) * inv_direction;
  vec3 t_lo = min(t0, t1);
  vec3 t_hi = max(t0, t1);
  float t_near = max(max(t_lo.x, t_lo.y), max(t_lo.z, tmin));
  float t_far = min(min(t_hi.x, t_hi.y), min(t_hi.z, tmax)) * kBvhBoxFarScale;
  return t_near <= t_far ? t_near : kBvhMiss;
}

// Möller–Trumbore. On a hit with tmin < t < tmax writes tuv = (t, u, v). Degenerate triangles and
// NaN inputs miss: every comparison is written so that NaN fails it.
LANTERN_FUNC bool bvh_ray_triangle(vec3 origin, vec3 direction, BvhTriangle tri, float tmin,
                                   float tmax, LANTERN_OUT(vec3) tuv) {
  vec3 e1 = vec3(tri.e1);
  vec3 e2 = vec3(tri.e2);
  vec3 p = cross(direction, e2);
  float det = dot(e1, p);
  tuv = vec3(0.0f);
  if (det == 0.0f) return false;
  float inv_det = 1.0f / det;
  vec3 s = origin - vec3(tri.v0);
  float u = dot(s, p) * inv_det;
  if (!(u >= 0.0f && u <= 1.0f)) return false;
  vec3 q = cross(s, e1);
  float v = dot(direction, q) * inv_det;
  if (!(v >= 0.0f && u + v <= 1.0f)) return false;
  float t = dot(e2, q) * inv_det;
  if (!(t > tmin && t < tmax)) return false;
  tuv = vec3(t, u, v);
  return true;
}

LANTERN_END_SHARED

#endif
