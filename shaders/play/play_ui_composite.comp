// play.ui_composite: the UI layer (premultiplied linear colour, cleared to 0 where no widget is)
// over the target's output image: output = ui.rgb + output.rgb * (1 - ui.a). Reads: ui layer.
// Writes: target (read-modify-write). History: none. Dispatch: one thread per pixel, 8x8 groups.
#version 460
#extension GL_GOOGLE_include_directive : require

#include "play/play_ui.h"

layout(local_size_x = 8, local_size_y = 8) in;

layout(binding = 0, rgba16f) uniform readonly image2D ui_layer;
layout(binding = 1, rgba32f) uniform image2D target;
layout(push_constant) uniform Push { PlayCompositePush push; };

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (p.x >= int(push.width) || p.y >= int(push.height)) return;
  vec4 ui = imageLoad(ui_layer, p);
  if (ui.a <= 0.0 && ui.r <= 0.0 && ui.g <= 0.0 && ui.b <= 0.0) return;
  vec4 c = imageLoad(target, p);
  float a = clamp(ui.a, 0.0, 1.0);
  imageStore(target, p, vec4(max(ui.rgb, vec3(0.0)) + c.rgb * (1.0 - a), 1.0));
}
