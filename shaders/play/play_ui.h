// Push constants of the play viewer's passes (apps/lantern/play/): play.ui (play_ui.vert/.frag),
// play.ui_composite (play_ui_composite.comp) and play.accumulate (play_accumulate.comp).
#ifndef LANTERN_PLAY_PLAY_UI_H
#define LANTERN_PLAY_PLAY_UI_H

#include "shared/lang.h"

LANTERN_BEGIN_SHARED

// One ImGui draw command: vertices and 32-bit indices are pulled from storage buffers.
struct PlayUiPush {
  vec4 scale_translate;  // xy: scale, zw: translate (ImGui pixels -> NDC)
  uint vertex_offset;    // first vertex of the command's list (in vertices)
  uint index_offset;     // first index of the command (in indices)
  uint font_width;       // font atlas size in texels (alpha, 4 texels per uint)
  uint font_height;
};
LANTERN_STATIC_SIZE(PlayUiPush, 32);

// play.ui_composite: output = ui.rgb + output.rgb * (1 - ui.a) (ui is premultiplied).
struct PlayCompositePush {
  uint width;
  uint height;
  uint pad0;
  uint pad1;
};
LANTERN_STATIC_SIZE(PlayCompositePush, 16);

// play.accumulate: sum += hdr (count == 1: sum = hdr), hdr = sum / count.
struct PlayAccumulatePush {
  uint pixels;
  uint count;  // frames in the sum including this one (>= 1)
  uint pad0;
  uint pad1;
};
LANTERN_STATIC_SIZE(PlayAccumulatePush, 16);

LANTERN_END_SHARED

#endif
