// GLSL visibility through the compute-shader BVH: binds the BVH buffers, defines the fetches that
// shaders/shared/bvh_traverse.h needs, and exposes bvh_trace_closest(BvhRay, out BvhHit),
// bvh_trace_any(BvhRay) and bvh_visible(origin, target) — the code the CPU tests run.
// Before including, a shader may define BVH_DESCRIPTOR_SET and BVH_BINDING_BASE (default 0 and 0;
// the four bindings are BASE + kBvhBinding*), and BVH_TEXEL_BUFFERS to read nodes, triangles and
// instances from rgba32ui uniform texel buffers (utextureBuffer) instead of storage buffers. Data is always
// fetched as uvec4 and bit-cast, so the uint fields packed in float lanes are never altered.
#ifndef LANTERN_LIB_BVH_TRAVERSE_GLSL
#define LANTERN_LIB_BVH_TRAVERSE_GLSL

#include "shared/bvh.h"

#ifndef BVH_DESCRIPTOR_SET
#define BVH_DESCRIPTOR_SET 0
#endif
#ifndef BVH_BINDING_BASE
#define BVH_BINDING_BASE 0
#endif

// Number of uvec4 per element of each array.
const uint kBvhNodeTexels = 2u;
const uint kBvhTriangleTexels = 3u;
const uint kBvhInstanceTexels = 9u;

layout(std430, set = BVH_DESCRIPTOR_SET, binding = BVH_BINDING_BASE + kBvhBindingHeader) readonly buffer
    BvhHeaderBuffer {
  BvhSceneHeader bvh_header;
};

#ifdef BVH_TEXEL_BUFFERS
// utextureBuffer (no sampler): a plain uniform texel buffer descriptor, read with texelFetch.
#extension GL_EXT_samplerless_texture_functions : require
layout(set = BVH_DESCRIPTOR_SET, binding = BVH_BINDING_BASE + kBvhBindingNodes) uniform utextureBuffer
    bvh_node_texels;
layout(set = BVH_DESCRIPTOR_SET, binding = BVH_BINDING_BASE + kBvhBindingTriangles) uniform utextureBuffer
    bvh_triangle_texels;
layout(set = BVH_DESCRIPTOR_SET, binding = BVH_BINDING_BASE + kBvhBindingInstances) uniform utextureBuffer
    bvh_instance_texels;
uvec4 bvh_node_texel(uint i) { return texelFetch(bvh_node_texels, int(i)); }
uvec4 bvh_triangle_texel(uint i) { return texelFetch(bvh_triangle_texels, int(i)); }
uvec4 bvh_instance_texel(uint i) { return texelFetch(bvh_instance_texels, int(i)); }
#else
layout(std430, set = BVH_DESCRIPTOR_SET, binding = BVH_BINDING_BASE + kBvhBindingNodes) readonly buffer
    BvhNodeBuffer {
  uvec4 bvh_node_data[];
};
layout(std430, set = BVH_DESCRIPTOR_SET, binding = BVH_BINDING_BASE + kBvhBindingTriangles) readonly buffer
    BvhTriangleBuffer {
  uvec4 bvh_triangle_data[];
};
layout(std430, set = BVH_DESCRIPTOR_SET, binding = BVH_BINDING_BASE + kBvhBindingInstances) readonly buffer
    BvhInstanceBuffer {
  uvec4 bvh_instance_data[];
};
uvec4 bvh_node_texel(uint i) { return bvh_node_data[i]; }
uvec4 bvh_triangle_texel(uint i) { return bvh_triangle_data[i]; }
uvec4 bvh_instance_texel(uint i) { return bvh_instance_data[i]; }
#endif

BvhSceneHeader bvh_fetch_header() { return bvh_header; }

BvhNode bvh_fetch_node(uint i) {
  BvhNode node;
  node.bounds_min = uintBitsToFloat(bvh_node_texel(kBvhNodeTexels * i));
  node.bounds_max = uintBitsToFloat(bvh_node_texel(kBvhNodeTexels * i + 1u));
  return node;
}

BvhTriangle bvh_fetch_triangle(uint i) {
  BvhTriangle tri;
  tri.v0 = uintBitsToFloat(bvh_triangle_texel(kBvhTriangleTexels * i));
  tri.e1 = uintBitsToFloat(bvh_triangle_texel(kBvhTriangleTexels * i + 1u));
  tri.e2 = uintBitsToFloat(bvh_triangle_texel(kBvhTriangleTexels * i + 2u));
  return tri;
}

// BvhInstance is object_to_world (texels 0-3, columns), world_to_object (4-7), offsets (8).
mat4 bvh_fetch_world_to_object(uint instance) {
  uint base = kBvhInstanceTexels * instance + 4u;
  return mat4(uintBitsToFloat(bvh_instance_texel(base)), uintBitsToFloat(bvh_instance_texel(base + 1u)),
              uintBitsToFloat(bvh_instance_texel(base + 2u)), uintBitsToFloat(bvh_instance_texel(base + 3u)));
}

uvec4 bvh_fetch_instance_offsets(uint instance) {
  return bvh_instance_texel(kBvhInstanceTexels * instance + 8u);
}

// The alpha-test hook (shared/bvh_traverse.h): the scene's material cutout where the scene
// buffers are declared (lib/scene_buffers.glsl defines scene_alpha_accept before including
// this), else every hit counts (standalone visibility probes).
bool bvh_accept_hit(uint instance, uint primitive, float u, float v) {
#ifdef LANTERN_SCENE_ALPHA_TEST
  return scene_alpha_accept(instance, primitive, u, v);
#else
  return true;
#endif
}

#include "shared/bvh_traverse.h"

#endif
