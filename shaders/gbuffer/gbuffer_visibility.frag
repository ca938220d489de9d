// gbuffer (fragment stage, visibility method): the closest surface's gbuffer.cull list entry into
// gbuffer.visibility (R32_UINT, cleared to kNoInstance = sky). With kTextured, a point an
// alpha-tested material cuts out is discarded (the depth test then keeps what lies behind);
// without, the scene buffers are declared but not read.
#version 460
#extension GL_GOOGLE_include_directive : require

#include "lib/scene_buffers.glsl"

layout(std430, binding = PASS_BINDING(1)) restrict readonly buffer TriangleBuffer {
  uvec2 t[];
} gbuffer_triangles;

#include "gbuffer/gbuffer_material.glsl"

layout(constant_id = 0) const bool kTextured = false;

#include "gbuffer/gbuffer_resolve.glsl"

layout(location = 0) flat in uint in_entry;
layout(location = 0) out uint out_visibility;

void main() {
  if (kTextured && gbuffer_resolve_alpha_cut(uvec2(gl_FragCoord.xy), gbuffer_triangles.t[in_entry]))
    discard;
  out_visibility = in_entry;
}
