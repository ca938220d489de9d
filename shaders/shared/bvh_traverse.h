// Two-level BVH traversal (closest hit and any hit), one source for the CPU (lighting/bvh/) and the
// GPU (shaders/lib/bvh_traverse.glsl). Memory is reached through five fetch functions: GLSL defines
// them before including this file; the C++ ones (below) take a BvhSceneView as first argument.
//   BvhNode bvh_fetch_node(uint i); BvhTriangle bvh_fetch_triangle(uint i);
//   mat4 bvh_fetch_world_to_object(uint instance); uvec4 bvh_fetch_instance_offsets(uint instance)
//   (x = node_offset, y = triangle_offset, z = user_id, w = flags); BvhSceneHeader
//   bvh_fetch_header(); and the alpha-test hook bool bvh_accept_hit(uint instance, uint
//   primitive, float u, float v), asked at each triangle hit of a kBvhInstanceAlphaTested instance.
#ifndef LANTERN_SHARED_BVH_TRAVERSE_H
#define LANTERN_SHARED_BVH_TRAVERSE_H

#include "shared/bvh.h"

#ifdef __cplusplus
namespace lantern::gpu {
// The CPU's view of the packed scene (lighting/bvh/scene_bvh.h owns the arrays).
struct BvhSceneView {
  const BvhNode* nodes = nullptr;
  const BvhTriangle* triangles = nullptr;
  const BvhInstance* instances = nullptr;
  BvhSceneHeader header{};
};
inline BvhSceneHeader bvh_fetch_header(const BvhSceneView& scene) {
  return scene.header;
}
inline BvhNode bvh_fetch_node(const BvhSceneView& scene, uint i) {
  return scene.nodes[i];
}
inline BvhTriangle bvh_fetch_triangle(const BvhSceneView& scene, uint i) {
  return scene.triangles[i];
}
inline mat4 bvh_fetch_world_to_object(const BvhSceneView& scene, uint instance) {
  return scene.instances[instance].world_to_object;
}
inline uvec4 bvh_fetch_instance_offsets(const BvhSceneView& scene, uint instance) {
  const BvhInstance& inst = scene.instances[instance];
  return uvec4(inst.node_offset, inst.triangle_offset, inst.user_id, inst.flags);
}
// The CPU traversal has no textures: every hit on an alpha-tested instance counts.
inline bool bvh_accept_hit(const BvhSceneView&, uint, uint, float, float) { return true; }
}  // namespace lantern::gpu

#define LANTERN_BVH_SCENE_PARAM const BvhSceneView &scene,
#define LANTERN_BVH_SCENE_ONLY_PARAM const BvhSceneView& scene
#define LANTERN_BVH_SCENE scene,
#define LANTERN_BVH_SCENE_ONLY scene
#else
#define LANTERN_BVH_SCENE_PARAM
#define LANTERN_BVH_SCENE_ONLY_PARAM
#define LANTERN_BVH_SCENE
#define LANTERN_BVH_SCENE_ONLY
#endif

LANTERN_BEGIN_SHARED

// The step of both traversals below at inner node `node_index` (node `node`) of the tree at
// node_base: the children whose boxes the ray reaches within [tmin, tmax], nearer first (the left
// one on a tie). Returns how many (0, 1 or 2); with one or two, node_index and node move to the
// nearer child, and with two, far_index and far_t name the farther one and its entry distance
// (the caller pushes them). With none, node_index and node stay.
LANTERN_FUNC uint bvh_children_reached(LANTERN_BVH_SCENE_PARAM uint node_base, vec3 origin,
                                       vec3 inv_direction, float tmin, float tmax,
                                       LANTERN_INOUT(uint) node_index, LANTERN_INOUT(BvhNode) node,
                                       LANTERN_OUT(uint) far_index, LANTERN_OUT(float) far_t) {
  uint left_index = node_index + 1u;
  uint right_index = bvh_node_index(node);
  BvhNode left = bvh_fetch_node(LANTERN_BVH_SCENE node_base + left_index);
  BvhNode right = bvh_fetch_node(LANTERN_BVH_SCENE node_base + right_index);
  float t_left =
      bvh_ray_box(origin, inv_direction, tmin, tmax, vec3(left.bounds_min), vec3(left.bounds_max));
  float t_right = bvh_ray_box(origin, inv_direction, tmin, tmax, vec3(right.bounds_min),
                              vec3(right.bounds_max));
  far_index = 0u;
  far_t = kBvhMiss;
  if (t_left <= t_right) {
    if (t_left == kBvhMiss) return 0u;
    node_index = left_index;
    node = left;
    far_index = right_index;
    far_t = t_right;
    return t_right != kBvhMiss ? 2u : 1u;
  }
  // t_right < t_left <= kBvhMiss: the right child is reached.
  node_index = right_index;
  node = right;
  far_index = left_index;
  far_t = t_left;
  return t_left != kBvhMiss ? 2u : 1u;
}

// Traverses one tree (the BLAS at node_offset) for the closest hit with t < hit.t, or stops at the
// first hit when any_hit is set. Returns whether it found a hit (and then updated `hit`). The
// nearer child is visited first; the farther one is pushed with its entry distance and skipped when
// popped behind a closer hit. Used for BLASes only: their leaves hold triangles.
LANTERN_FUNC bool bvh_traverse_blas(LANTERN_BVH_SCENE_PARAM uint node_offset, uint triangle_offset,
                                    uint instance, uint instance_flags, vec3 origin,
                                    vec3 direction, float tmin, bool any_hit,
                                    LANTERN_INOUT(BvhHit) hit) {
  vec3 inv_direction = bvh_safe_reciprocal(direction);
  BvhNode root = bvh_fetch_node(LANTERN_BVH_SCENE node_offset);
  if (bvh_ray_box(origin, inv_direction, tmin, hit.t, vec3(root.bounds_min),
                  vec3(root.bounds_max)) == kBvhMiss)
    return false;
  uint stack_node[kBvhStackSize];
  float stack_t[kBvhStackSize];
  uint stack_size = 0u;
  uint node_index = 0u;
  BvhNode node = root;
  bool found = false;
  while (true) {
    if (bvh_node_is_leaf(node)) {
      uint first = bvh_node_index(node);
      uint count = bvh_node_count(node);
      for (uint i = 0u; i < count; ++i) {
        BvhTriangle tri = bvh_fetch_triangle(LANTERN_BVH_SCENE triangle_offset + first + i);
        vec3 tuv;
        if (bvh_ray_triangle(origin, direction, tri, tmin, hit.t, tuv) &&
            ((instance_flags & kBvhInstanceAlphaTested) == 0u ||
             bvh_accept_hit(LANTERN_BVH_SCENE instance, floatBitsToUint(tri.v0.w), tuv.y, tuv.z))) {
          hit.t = tuv.x;
          hit.u = tuv.y;
          hit.v = tuv.z;
          hit.primitive = floatBitsToUint(tri.v0.w);
          hit.instance = floatBitsToUint(tri.e1.w);  // a merged triangle's own instance + 1
          found = true;
          if (any_hit) return true;
        }
      }
    } else {
      uint far_index;
      float far_t;
      uint reached = bvh_children_reached(LANTERN_BVH_SCENE node_offset, origin, inv_direction,
                                          tmin, hit.t, node_index, node, far_index, far_t);
      if (reached == 2u) {
        stack_node[stack_size] = far_index;
        stack_t[stack_size] = far_t;
        ++stack_size;
      }
      if (reached > 0u) continue;
    }
    // Pop the next subtree that still starts before the closest hit so far.
    bool popped = false;
    while (stack_size > 0u && !popped) {
      --stack_size;
      popped = stack_t[stack_size] < hit.t;
    }
    if (!popped) break;
    node_index = stack_node[stack_size];
    node = bvh_fetch_node(LANTERN_BVH_SCENE node_offset + node_index);
  }
  return found;
}

// Moves the ray into the instance's object space (affine: t and barycentrics are unchanged) and
// traverses its BLAS.
LANTERN_FUNC bool bvh_traverse_instance(LANTERN_BVH_SCENE_PARAM uint instance, vec3 origin,
                                        vec3 direction, float tmin, bool any_hit,
                                        LANTERN_INOUT(BvhHit) hit) {
  mat4 world_to_object = bvh_fetch_world_to_object(LANTERN_BVH_SCENE instance);
  uvec4 offsets = bvh_fetch_instance_offsets(LANTERN_BVH_SCENE instance);
  vec3 object_origin = vec3(world_to_object * vec4(origin, 1.0f));
  vec3 object_direction = vec3(world_to_object * vec4(direction, 0.0f));
  if (!bvh_traverse_blas(LANTERN_BVH_SCENE offsets.x, offsets.y, instance, offsets.w,
                         object_origin, object_direction, tmin, any_hit, hit))
    return false;
  // Triangles of the merged tree of fixed instances name their own instance (shared/bvh.h).
  uint source = hit.instance;
  hit.instance = source == 0u ? instance : source - 1u;
  hit.user_id =
      source == 0u ? offsets.z : bvh_fetch_instance_offsets(LANTERN_BVH_SCENE hit.instance).z;
  return true;
}

// Traverses the TLAS (header.tlas_node_count nodes from tlas_node_offset, one instance per leaf)
// and the BLAS of every instance whose world box the ray reaches, in the same order as above.
LANTERN_FUNC bool bvh_traverse_scene(LANTERN_BVH_SCENE_PARAM BvhRay ray, bool any_hit,
                                     LANTERN_INOUT(BvhHit) hit) {
  vec3 origin = vec3(ray.origin);
  vec3 direction = vec3(ray.direction);
  float tmin = ray.origin.w;
  hit.t = ray.direction.w;
  hit.u = 0.0f;
  hit.v = 0.0f;
  hit.instance = 0u;
  hit.primitive = 0u;
  hit.user_id = 0u;
  hit.pad0 = 0u;
  hit.pad1 = 0u;
  BvhSceneHeader header = bvh_fetch_header(LANTERN_BVH_SCENE_ONLY);
  if (header.tlas_node_count == 0u) return false;
  // NaN or infinite rays miss: the slab and triangle tests are only NaN-safe for finite rays.
  float finite_check = dot(origin, origin) + dot(direction, direction) + tmin;
  if (isnan(finite_check) || isinf(finite_check) || isnan(hit.t)) return false;
  vec3 inv_direction = bvh_safe_reciprocal(direction);
  uint tlas = header.tlas_node_offset;
  BvhNode node = bvh_fetch_node(LANTERN_BVH_SCENE tlas);
  if (bvh_ray_box(origin, inv_direction, tmin, hit.t, vec3(node.bounds_min),
                  vec3(node.bounds_max)) == kBvhMiss)
    return false;
  uint stack_node[kBvhStackSize];
  float stack_t[kBvhStackSize];
  uint stack_size = 0u;
  uint node_index = 0u;
  bool found = false;
  while (true) {
    if (bvh_node_is_leaf(node)) {
      if (bvh_traverse_instance(LANTERN_BVH_SCENE bvh_node_index(node), origin, direction, tmin,
                                any_hit, hit)) {
        found = true;
        if (any_hit) return true;
      }
    } else {
      uint far_index;
      float far_t;
      uint reached = bvh_children_reached(LANTERN_BVH_SCENE tlas, origin, inv_direction, tmin,
                                          hit.t, node_index, node, far_index, far_t);
      if (reached == 2u) {
        stack_node[stack_size] = far_index;
        stack_t[stack_size] = far_t;
        ++stack_size;
      }
      if (reached > 0u) continue;
    }
    bool popped = false;
    while (stack_size > 0u && !popped) {
      --stack_size;
      popped = stack_t[stack_size] < hit.t;
    }
    if (!popped) break;
    node_index = stack_node[stack_size];
    node = bvh_fetch_node(LANTERN_BVH_SCENE tlas + node_index);
  }
  return found;
}

// Closest hit along the ray segment.
LANTERN_FUNC bool bvh_trace_closest(LANTERN_BVH_SCENE_PARAM BvhRay ray, LANTERN_OUT(BvhHit) hit) {
  return bvh_traverse_scene(LANTERN_BVH_SCENE ray, false, hit);
}

// Whether anything lies on the ray segment (shadow ray; stops at the first hit).
LANTERN_FUNC bool bvh_trace_any(LANTERN_BVH_SCENE_PARAM BvhRay ray) {
  BvhHit hit;
  return bvh_traverse_scene(LANTERN_BVH_SCENE ray, true, hit);
}

// Shadow ray between two surface points: true when nothing blocks the segment. Both ends are
// pulled in by kBvhShadowEpsilon scaled to the coordinates' magnitude, so neither the surface the
// ray leaves nor the one it reaches counts as a blocker.
// (bvh_shadow_t_epsilon in shared/bvh.h: the one epsilon policy, also used by the ray-query
// backend of shaders/lib/visibility.glsl.)
LANTERN_FUNC bool bvh_visible(LANTERN_BVH_SCENE_PARAM vec3 origin, vec3 target) {
  float t_epsilon = bvh_shadow_t_epsilon(origin, target);
  if (t_epsilon < 0.0f) return true;
  return !bvh_trace_any(
      LANTERN_BVH_SCENE bvh_make_ray(origin, target - origin, t_epsilon, 1.0f - t_epsilon));
}

LANTERN_END_SHARED

#endif
