// play.ui (vertex): ImGui's draw lists, pulled from storage buffers (no vertex input). An ImDrawVert
// is 5 words: pos.xy, uv.xy (floats), colour (RGBA8, sRGB). Outputs linear colour for blending in
// linear space (target.present encodes sRGB). See apps/lantern/play/play_ui.cpp.
#version 460
#extension GL_GOOGLE_include_directive : require

#include "play/play_ui.h"

layout(std430, binding = 0) readonly buffer UiVertices { uint words[]; } ui_vertices;
layout(std430, binding = 1) readonly buffer UiIndices { uint values[]; } ui_indices;
layout(push_constant) uniform Push { PlayUiPush push; };

layout(location = 0) out vec4 out_color;
layout(location = 1) out vec2 out_uv;

vec3 srgb_to_linear(vec3 c) {
  return mix(c / 12.92, pow((c + 0.055) / 1.055, vec3(2.4)), greaterThan(c, vec3(0.04045)));
}

void main() {
  uint v = ui_indices.values[push.index_offset + uint(gl_VertexIndex)] + push.vertex_offset;
  uint base = v * 5u;
  vec2 pos = vec2(uintBitsToFloat(ui_vertices.words[base]),
                  uintBitsToFloat(ui_vertices.words[base + 1u]));
  out_uv = vec2(uintBitsToFloat(ui_vertices.words[base + 2u]),
                uintBitsToFloat(ui_vertices.words[base + 3u]));
  vec4 c = unpackUnorm4x8(ui_vertices.words[base + 4u]);
  out_color = vec4(srgb_to_linear(c.rgb), c.a);
  gl_Position = vec4(pos * push.scale_translate.xy + push.scale_translate.zw, 0.0, 1.0);
}
