// Push constants and constants of the gbuffer passes (shaders/gbuffer/*), shared with
// lighting/gbuffer/gbuffer_pass.cpp.
#ifndef LANTERN_GBUFFER_GBUFFER_PUSH_H
#define LANTERN_GBUFFER_GBUFFER_PUSH_H

#include "shared/lang.h"

LANTERN_BEGIN_SHARED

// gbuffer (forward method): the instance the current draw rasterises (one draw per instance).
struct GBufferPush {
  uint instance;
};
LANTERN_STATIC_SIZE(GBufferPush, 4);

// gbuffer.draws / gbuffer.cull: how many instances the frame draws, and how many triangle
// records gbuffer.cull may write (the sum of the instances' triangles).
struct GBufferDrawsPush {
  uint instance_count;
  uint triangle_capacity;
};
LANTERN_STATIC_SIZE(GBufferDrawsPush, 8);

// Triangles per gbuffer.cull workgroup (= its local size): an instance's triangles are cut into
// chunks of this many, and one workgroup culls one chunk of one instance.
LANTERN_CONST uint kGBufferCullChunk = 128u;

LANTERN_END_SHARED

#endif
