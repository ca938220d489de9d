// Push constants of frame.output (shaders/frame/frame_output.comp), shared with
// lighting/frame/frame_output_pass.cpp.
#ifndef LANTERN_FRAME_FRAME_OUTPUT_H
#define LANTERN_FRAME_FRAME_OUTPUT_H

#include "shared/lang.h"

LANTERN_BEGIN_SHARED

struct FrameOutputPush {
  uint width;
  uint height;
  float exposure;  // 0: copy linear radiance; > 0: exposure x filmic tonemap (display linear)
  uint pad0;
};
LANTERN_STATIC_SIZE(FrameOutputPush, 16);

LANTERN_END_SHARED

#endif
