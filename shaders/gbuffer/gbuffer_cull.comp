// gbuffer.cull: finds the triangles that can cover a pixel centre this frame and lists them for
// the visibility raster, so lavapipe's single-threaded raster front end (vertex shading, setup,
// binning: ~0.1-0.2 us per triangle) only sees those. A triangle is dropped when all three clip
// corners lie outside one clip plane, or (all corners in front of the camera) when its
// screen-space bounding box, grown by kMargin pixels, holds no pixel centre of the image, or when
// it holds at most four and none of them lies inside the triangle grown by kMargin pixels.
// kMargin (1/64 px) is wider than lavapipe's vertex snapping (1/256 px), so a dropped triangle
// could not have produced a fragment; what survives is rasterised exactly as before.
// Reads: scene frame_constants, vertices, indices, instances, gbuffer_chunks, gbuffer_dispatch
// (indirect). Writes: gbuffer_triangles ((instance, triangle) per survivor), gbuffer_clip (three
// clip positions per survivor), gbuffer_draw.x (+3 per survivor). History: none.
// Dispatch: indirect, one workgroup of kGBufferCullChunk threads per chunk of one instance.
#version 460
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_ballot : require

#include "gbuffer/gbuffer_push.h"
#include "shared/gbuffer.h"
#include "lib/scene_buffers.glsl"

layout(local_size_x = 128) in;

layout(std430, binding = PASS_BINDING(0)) restrict readonly buffer ChunkBuffer {
  uint first[];
} gbuffer_chunks;
layout(std430, binding = PASS_BINDING(1)) writeonly buffer TriangleBuffer {
  uvec2 t[];
} gbuffer_triangles;
layout(std430, binding = PASS_BINDING(2)) writeonly buffer ClipBuffer { vec4 p[]; } gbuffer_clip;
layout(std430, binding = PASS_BINDING(3)) coherent buffer DrawBuffer {
  uint vertex_count;
} gbuffer_draw;

layout(push_constant) uniform Push { GBufferDrawsPush push; };

const float kMargin = 1.0 / 64.0;

// Whether pixel centre c lies inside triangle (a, b, d) grown by kMargin pixels (either winding).
bool covers(vec2 a, vec2 b, vec2 d, vec2 c) {
  vec3 e = vec3((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x),
                (d.x - b.x) * (c.y - b.y) - (d.y - b.y) * (c.x - b.x),
                (a.x - d.x) * (c.y - d.y) - (a.y - d.y) * (c.x - d.x));
  vec3 tolerance = kMargin * vec3(length(b - a), length(d - b), length(a - d));
  return all(greaterThanEqual(e, -tolerance)) || all(lessThanEqual(e, tolerance));
}

bool survives(vec4 c0, vec4 c1, vec4 c2) {
  // Outside one clip plane (exact for clipping: no part of the triangle can be inside).
  if (c0.x > c0.w && c1.x > c1.w && c2.x > c2.w) return false;
  if (c0.x < -c0.w && c1.x < -c1.w && c2.x < -c2.w) return false;
  if (c0.y > c0.w && c1.y > c1.w && c2.y > c2.w) return false;
  if (c0.y < -c0.w && c1.y < -c1.w && c2.y < -c2.w) return false;
  if (c0.z > c0.w && c1.z > c1.w && c2.z > c2.w) return false;
  if (c0.z < 0.0 && c1.z < 0.0 && c2.z < 0.0) return false;
  if (!(c0.w > 0.0 && c1.w > 0.0 && c2.w > 0.0)) return true;  // crosses the camera plane
  vec2 size = vec2(frame_constants.frame.frame.xy);
  vec2 s0 = (c0.xy / c0.w * 0.5 + 0.5) * size;
  vec2 s1 = (c1.xy / c1.w * 0.5 + 0.5) * size;
  vec2 s2 = (c2.xy / c2.w * 0.5 + 0.5) * size;
  vec2 lo = min(s0, min(s1, s2)) - kMargin;
  vec2 hi = max(s0, max(s1, s2)) + kMargin;
  // Pixel centres k + 0.5 inside [lo, hi], clamped to the image.
  vec2 k0 = max(ceil(lo - 0.5), vec2(0.0));
  vec2 k1 = min(floor(hi - 0.5), size - 1.0);
  if (!(k0.x <= k1.x && k0.y <= k1.y)) return false;  // also false for NaN
  vec2 extent = k1 - k0;
  if (extent.x > 1.0 || extent.y > 1.0) return true;
  for (float y = k0.y; y <= k1.y; y += 1.0) {
    for (float x = k0.x; x <= k1.x; x += 1.0) {
      if (covers(s0, s1, s2, vec2(x, y) + 0.5)) return true;
    }
  }
  return false;
}

// Per-workgroup values (one instance per workgroup), computed by its first invocation so the
// other lanes read them from shared memory instead of gathering them from storage buffers.
shared uint shared_instance;
shared uint shared_first_chunk;
shared uvec4 shared_geometry;
shared mat4 shared_to_clip;

void main() {
  uint chunk = gl_WorkGroupID.x;
  if (gl_LocalInvocationIndex == 0u) {
    // The instance owning this chunk: the last one whose first chunk <= the chunk.
    uint lo = 0u, hi = push.instance_count;  // invariant: first[lo] <= chunk < first[hi]
    while (hi - lo > 1u) {
      uint mid = (lo + hi) / 2u;
      if (gbuffer_chunks.first[mid] <= chunk) lo = mid; else hi = mid;
    }
    shared_instance = lo;
    shared_first_chunk = gbuffer_chunks.first[lo];
    shared_geometry = scene_instances.i[lo].geometry;
    shared_to_clip = frame_constants.frame.view_proj * scene_instances.i[lo].object_to_world;
  }
  barrier();
  uint instance = shared_instance;
  uvec4 geometry = shared_geometry;
  uint triangle = (chunk - shared_first_chunk) * kGBufferCullChunk + gl_LocalInvocationID.x;
  bool keep = false;
  vec4 c0, c1, c2;
  if (triangle < geometry.z / 3u) {
    mat4 to_clip = shared_to_clip;
    uint base = geometry.y + 3u * triangle;
    c0 = to_clip *
         vec4(scene_vertices.v[geometry.w + scene_indices.i[base]].position_u.xyz, 1.0);
    c1 = to_clip *
         vec4(scene_vertices.v[geometry.w + scene_indices.i[base + 1u]].position_u.xyz, 1.0);
    c2 = to_clip *
         vec4(scene_vertices.v[geometry.w + scene_indices.i[base + 2u]].position_u.xyz, 1.0);
    // The raster samples at centre + jitter: test (and write) the jittered clip positions.
    vec2 size = vec2(frame_constants.frame.frame.xy);
    vec2 jitter = frame_constants.frame.jitter.xy;
    c0 = gbuffer_jitter_clip(c0, jitter, size);
    c1 = gbuffer_jitter_clip(c1, jitter, size);
    c2 = gbuffer_jitter_clip(c2, jitter, size);
    keep = survives(c0, c1, c2);
  }
  // One atomic per subgroup: survivors take consecutive slots.
  uvec4 ballot = subgroupBallot(keep);
  uint survivors = subgroupBallotBitCount(ballot);
  if (survivors == 0u) return;
  uint base_vertex = 0u;
  if (subgroupElect()) base_vertex = atomicAdd(gbuffer_draw.vertex_count, 3u * survivors);
  base_vertex = subgroupBroadcastFirst(base_vertex);
  if (!keep) return;
  uint slot = base_vertex / 3u + subgroupBallotExclusiveBitCount(ballot);
  if (slot >= push.triangle_capacity) return;  // cannot happen with a correct capacity

  gbuffer_triangles.t[slot] = uvec2(instance, triangle);
  gbuffer_clip.p[3u * slot] = c0;
  gbuffer_clip.p[3u * slot + 1u] = c1;
  gbuffer_clip.p[3u * slot + 2u] = c2;
}
