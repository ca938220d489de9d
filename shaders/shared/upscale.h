// Push constants of upscale.temporal (shaders/upscale/upscale_temporal.comp), shared with
// lighting/upscale/upscaler.cpp: the internal (render) size, the output size, how much of the
// reprojected output history each pixel keeps, and the sub-pixel jitter of this frame's samples
// (FrameConstants.jitter.xy).
#ifndef LANTERN_SHARED_UPSCALE_H
#define LANTERN_SHARED_UPSCALE_H

#include "shared/lang.h"

LANTERN_BEGIN_SHARED

LANTERN_CONST uint kUpscaleFlagHistoryValid = 1u;  // the graph handed last frame's output

struct UpscalePush {
  uint in_width;
  uint in_height;
  uint out_width;
  uint out_height;
  uint flags;            // kUpscaleFlag*
  float history_weight;  // share of the (rectified) history kept: 0 = this frame's samples only
  vec2 jitter;           // this frame's sample offset from the internal pixel centres, pixels
};
LANTERN_STATIC_SIZE(UpscalePush, 32);

LANTERN_END_SHARED

#endif
