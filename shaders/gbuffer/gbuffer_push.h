// Push constants of the gbuffer passes (shaders/gbuffer/gbuffer.{vert,frag},
// shaders/gbuffer/gbuffer_draws.comp), shared with lighting/gbuffer/gbuffer_pass.cpp.
#ifndef LANTERN_GBUFFER_GBUFFER_PUSH_H
#define LANTERN_GBUFFER_GBUFFER_PUSH_H

#include "shared/lang.h"

LANTERN_BEGIN_SHARED

// gbuffer: the instance the current draw rasterises (one draw per instance).
struct GBufferPush {
  uint instance;
};
LANTERN_STATIC_SIZE(GBufferPush, 4);

// gbuffer.draws: how many instances get a draw command.
struct GBufferDrawsPush {
  uint instance_count;
};
LANTERN_STATIC_SIZE(GBufferDrawsPush, 4);

// Motion written where the surface point lies behind the previous camera (no previous pixel):
// it moves the previous position far off-screen, so temporal passes find no history there.
LANTERN_CONST float kGBufferNoPreviousPixel = -1.0e6f;

LANTERN_END_SHARED

#endif
