// play.ui (fragment): vertex colour times the font atlas alpha (one byte per texel, packed four
// to a word, nearest texel: ImGui draws its glyphs at 1:1). Blended "over" into the UI layer.
#version 460
#extension GL_GOOGLE_include_directive : require

#include "play/play_ui.h"

layout(std430, binding = 2) readonly buffer UiFont { uint texels[]; } ui_font;
layout(push_constant) uniform Push { PlayUiPush push; };

layout(location = 0) in vec4 in_color;
layout(location = 1) in vec2 in_uv;
layout(location = 0) out vec4 out_color;

void main() {
  uvec2 size = uvec2(push.font_width, push.font_height);
  uvec2 t = min(uvec2(clamp(in_uv, 0.0, 1.0) * vec2(size)), size - 1u);
  uint i = t.y * size.x + t.x;
  float alpha = float((ui_font.texels[i >> 2u] >> ((i & 3u) * 8u)) & 0xffu) / 255.0;
  out_color = vec4(in_color.rgb, in_color.a * alpha);
}
