// gbuffer (vertex stage): vertex pulling from the scene's storage buffers. One non-indexed draw
// per instance (push.instance) of geometry.z vertices: vertex k is corner k % 3 of triangle
// k / 3, whose mesh-relative indices start at geometry.y and vertices at geometry.w (as
// surface_at in shaders/integrators/baseline.comp). The triangle's geometric normal is computed
// here from its three world-space corners (winding e1 x e2, mirrored by a negative determinant)
// and passed flat, with the instance, material and primitive ids. The clip positions without
// jitter, this frame's and last frame's (prev_object_to_world, prev_view_proj), are interpolated
// for the motion vector (gbuffer_point_motion), and the
// texcoords (both sets) for the material's textures.
#version 460
#extension GL_GOOGLE_include_directive : require

#include "gbuffer/gbuffer_push.h"
#include "shared/gbuffer.h"
#include "lib/scene_buffers.glsl"


layout(push_constant) uniform Push { GBufferPush push; };

layout(location = 0) out vec3 out_world;
layout(location = 1) out vec3 out_shading_normal;  // world space, not normalised
layout(location = 2) out vec4 out_prev_clip;
layout(location = 3) flat out vec3 out_geometric_normal;  // front face, unit (or zero)
layout(location = 4) flat out uvec3 out_ids;              // instance, material, primitive
layout(location = 5) out vec2 out_uv;                     // TEXCOORD_0
layout(location = 6) out vec2 out_uv1;                    // TEXCOORD_1 (zero without one)
layout(location = 7) out vec4 out_clip;                   // view_proj x world, no jitter

void main() {
  uint instance = push.instance;
  mat4 object_to_world = scene_instances.i[instance].object_to_world;
  uvec4 geometry = scene_instances.i[instance].geometry;
  uint primitive = uint(gl_VertexIndex) / 3u;
  uint corner = uint(gl_VertexIndex) - 3u * primitive;
  uint base = geometry.y + 3u * primitive;
  uint first_vertex = geometry.w;
  vec3 p0 = scene_vertices.v[first_vertex + scene_indices.i[base]].position_u.xyz;
  vec3 p1 = scene_vertices.v[first_vertex + scene_indices.i[base + 1u]].position_u.xyz;
  vec3 p2 = scene_vertices.v[first_vertex + scene_indices.i[base + 2u]].position_u.xyz;
  vec3 p = corner == 0u ? p0 : (corner == 1u ? p1 : p2);
  uint vertex_index = first_vertex + scene_indices.i[base + corner];
  GpuVertex vertex = scene_vertices.v[vertex_index];
  vec3 n_object = vertex.normal_v.xyz;
  out_uv = vec2(vertex.position_u.w, vertex.normal_v.w);
  out_uv1 = scene_vertex_texcoord(vertex_index, 1u);

  mat3 linear = mat3(object_to_world);
  vec3 ng = cross(linear * (p1 - p0), linear * (p2 - p0));
  if (determinant(linear) < 0.0) ng = -ng;
  float ng_len2 = dot(ng, ng);
  out_geometric_normal = ng_len2 > 0.0 ? ng * inversesqrt(ng_len2) : vec3(0.0);

  vec4 world = object_to_world * vec4(p, 1.0);
  vec4 prev_world = scene_instances.i[instance].prev_object_to_world * vec4(p, 1.0);
  out_world = world.xyz;
  out_shading_normal = transpose(mat3(scene_instances.i[instance].world_to_object)) * n_object;
  out_prev_clip = frame_constants.frame.prev_view_proj * prev_world;
  out_clip = frame_constants.frame.view_proj * world;
  out_ids = uvec3(instance, geometry.x, primitive);
  gl_Position = gbuffer_jitter_clip(out_clip, frame_constants.frame.jitter.xy,
                                    vec2(frame_constants.frame.frame.xy));
}
