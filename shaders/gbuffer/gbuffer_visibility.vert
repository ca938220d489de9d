// gbuffer (vertex stage, visibility method): one draw over the triangles gbuffer.cull kept;
// vertex k is corner k % 3 of list entry k / 3, whose clip position gbuffer.cull computed. Only
// the clip position and the flat list index leave this stage (lavapipe's per-triangle setup cost
// grows with every varying; gbuffer.resolve reconstructs the rest per pixel).
#version 460
#extension GL_GOOGLE_include_directive : require

#include "shared/scene_bindings.h"

// After the scene's slots: the fragment stage reads the scene buffers (alpha cutouts).
layout(std430, binding = kPassBindingBase) readonly buffer ClipBuffer { vec4 p[]; } gbuffer_clip;

layout(location = 0) flat out uint out_entry;

void main() {
  out_entry = uint(gl_VertexIndex) / 3u;
  gl_Position = gbuffer_clip.p[gl_VertexIndex];
}
