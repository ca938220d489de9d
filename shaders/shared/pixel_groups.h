// The workgroup shape of the per-pixel compute passes (denoise.*, upscale.temporal): a
// specialisation constant per axis, which lighting/frame/tile_order.h's pixel_group_shape()
// sets per device, and the square GPU shape as the default.
// On a CPU device (lavapipe) the groups are rows: an invocation vector runs along x either way,
// but an 8x8 group walks 8 image rows (5 KiB apart at 320 pixels of vec4) in every buffer it
// reads or writes, and the passes that touch many buffers per pixel ran about twice as long
// (denoise.temporal, ~20 buffers and images: 6.2 ms in 8x8, 2.7 ms in 64x1 or 32x2 groups, 4x2
// and 8x1 alike, 16x4 and 32x4 as slow as 8x8, night_market 320x180); those that read a few
// buffers (the à-trous steps) did not move. GPUs keep the square tile their caches are built for.
#ifndef LANTERN_SHARED_PIXEL_GROUPS_H
#define LANTERN_SHARED_PIXEL_GROUPS_H

#include "shared/lang.h"

LANTERN_BEGIN_SHARED

// Specialisation constant ids of the group's width and height.
LANTERN_CONST uint kPixelGroupWidthId = 0u;
LANTERN_CONST uint kPixelGroupHeightId = 1u;
// Threads per side of a group on a GPU (the shaders' default).
LANTERN_CONST uint kPixelGroupGpuSide = 8u;
// Threads of a group's one row on a CPU device.
LANTERN_CONST uint kPixelGroupCpuWidth = 64u;

LANTERN_END_SHARED

#endif
