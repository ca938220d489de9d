// The workgroup shape of a per-pixel pass (shared/pixel_groups.h): kPixelGroupGpuSide squared
// unless the pipeline specialises it (lighting/frame/tile_order.h, pixel_group_constants: rows on
// CPU devices). A pass that includes this maps its threads to pixels by gl_GlobalInvocationID
// (denoise.*, upscale.temporal) or its workgroups to tiles of this shape (pixel_tile_origin:
// restir.*, integrators.*).
#ifndef LANTERN_LIB_PIXEL_GROUPS_GLSL
#define LANTERN_LIB_PIXEL_GROUPS_GLSL

#include "shared/pixel_groups.h"

layout(local_size_x = kPixelGroupGpuSide, local_size_y = kPixelGroupGpuSide,
       local_size_x_id = kPixelGroupWidthId, local_size_y_id = kPixelGroupHeightId) in;

#endif
