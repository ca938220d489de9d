// The workgroup shape of the per-pixel compute passes (denoise.*, upscale.temporal, and the tiles
// of restir.* and integrators.*): a specialisation constant per axis, which
// lighting/frame/tile_order.h's pixel_group_constants() sets per device (restir.initial keeps
// the square on every device: lighting/restir/restir_pass.cpp), and the square GPU shape as the
// default; and the order in which tile passes visit the image (pixel_tile_origin).
// On a CPU device (lavapipe) the groups are rows: an invocation vector runs along x either way,
// but an 8x8 group walks 8 image rows (5 KiB apart at 320 pixels of vec4) in every buffer it
// reads or writes, and the passes that touch many buffers per pixel ran up to twice as long
// (night_market 320x180: denoise.temporal, ~20 buffers and images, 6.2 ms in 8x8 groups, 2.7 ms
// in 64x1 or 32x2, 4x2 and 8x1 alike, 16x4 and 32x4 as slow as 8x8; restir.temporal 5.6 -> 4.6,
// restir.shade 2.8 -> 2.0); those that read a few buffers (the à-trous steps, restir.spatial) did
// not move. GPUs keep the square tile their caches are built for.
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
// Threads of a group in either shape (restir.initial's local light list has a slot per thread,
// restir.temporal's boiling filter a weight).
LANTERN_CONST uint kPixelGroupThreads = 64u;
#ifdef __cplusplus
static_assert(kPixelGroupGpuSide * kPixelGroupGpuSide == kPixelGroupThreads &&
              kPixelGroupCpuWidth == kPixelGroupThreads);
#endif

// Tile g of a dispatch (tiles of the group's shape `tile`, one workgroup each) -> its top-left
// pixel. With bands > 0 (CPU devices: lavapipe hands each of its `bands` threads a contiguous run
// of workgroups), the workgroups walk rows of tiles in order, row t, t + bands, t + 2 bands, ...
// for the t-th run: each thread sees the whole image's height (sky and geometry alike) while its
// consecutive workgroups stay side by side and its rows close together, so the neighbours the
// reuse passes read stay in its cache. With bands == 0, tile (g * stride) mod count: neighbouring
// workgroups land far apart, and each lavapipe thread gets a mix of sky and geometry. Either way
// a permutation of the tiles.
LANTERN_FUNC uvec2 pixel_tile_origin(uint group, uint stride, uint bands, uvec2 size, uvec2 tile) {
  uint tiles_x = (size.x + tile.x - 1u) / tile.x;
  uint tiles_y = (size.y + tile.y - 1u) / tile.y;
  if (bands == 0u || tiles_x == 0u || tiles_y == 0u) {
    uint t = (group * stride) % max(tiles_x * tiles_y, 1u);
    return uvec2(t % tiles_x, t / tiles_x) * tile;
  }
  // The k-th row of the sequence: the first `longer` bands hold q + 1 rows, the others q.
  uint k = group / tiles_x;
  uint q = tiles_y / bands;
  uint longer = tiles_y % bands;
  uint band;
  uint i;
  if (k < longer * (q + 1u)) {
    band = k / (q + 1u);
    i = k % (q + 1u);
  } else {
    uint rest = k - longer * (q + 1u);
    band = longer + rest / max(q, 1u);
    i = rest % max(q, 1u);
  }
  return uvec2(group % tiles_x, band + i * bands) * tile;
}

LANTERN_END_SHARED

#endif
