// The light grid: the lights binned by where they are, in a uniform grid of world-space cells
// over the lights' bounds (built on the CPU by lighting/lights/light_grid.cpp, read by
// restir.initial's grid candidates: a light drawn near the shading point, whose density any
// light's own cell record gives back in O(1)).
// A light's place: a triangle's centroid, a point or spot light's position; a directional light
// has none (it is in no cell, and the grid never draws it).
// Drawing near x: one of the 3x3x3 cells around x's cell, uniformly, then one light of that cell
// uniformly (nothing when the cell is empty or outside the grid); light l is drawn with
// probability [l's cell is one of the 27] / (27 x its cell's light count): light_grid_pdf.
#ifndef LANTERN_SHARED_LIGHT_GRID_H
#define LANTERN_SHARED_LIGHT_GRID_H

#include "shared/lang.h"

LANTERN_BEGIN_SHARED

// Cells per axis are at most kLightGridAxisCells (a cell's key packs x, y, z in 10 bits each),
// and at most kLightGridMaxCells in all (the cell table is dense: 8 bytes a cell).
LANTERN_CONST uint kLightGridAxisCells = 1024u;
LANTERN_CONST uint kLightGridMaxCells = 1u << 20u;
LANTERN_CONST uint kLightGridNoCell = 0xffffffffu;  // the key of a light in no cell
LANTERN_CONST uint kLightGridNeighbourCells = 27u;  // the 3x3x3 cells a draw picks from

struct GpuLightGrid {
  vec4 origin_cell;  // xyz: the grid's lowest corner (world); w: cell edge length (0: no grid)
  uvec4 dims;        // xyz: cells per axis; w: lights in cells
};
LANTERN_STATIC_SIZE(GpuLightGrid, 32);

// scene.light_grid holds the header, then as 32-bit words the dense table of cells (x fastest,
// then y, then z; two words each: GpuLightGridCell) and the light indices, cell by cell.
// One cell of the dense table: its lights' range in the grid's list.
struct GpuLightGridCell {
  uint first;  // first of its lights in the grid's light list
  uint count;  // its lights (0: an empty cell)
};
LANTERN_STATIC_SIZE(GpuLightGridCell, 8);

// Words of the dense table after the header: where the cell-ordered light list starts.
LANTERN_FUNC uint light_grid_cell_words(GpuLightGrid grid) {
  return 2u * grid.dims.x * grid.dims.y * grid.dims.z;
}

// Integer cell of world point p, clamped into the grid (every light's and every point's).
LANTERN_FUNC uvec4 light_grid_cell(GpuLightGrid grid, vec3 p) {
  vec3 c = floor((p - vec3(grid.origin_cell)) / grid.origin_cell.w);
  vec3 hi = vec3(float(grid.dims.x - 1u), float(grid.dims.y - 1u), float(grid.dims.z - 1u));
  c = clamp(c, vec3(0.0f), hi);
  return uvec4(uint(c.x), uint(c.y), uint(c.z), 0u);
}

LANTERN_FUNC uint light_grid_key(uvec4 cell) { return cell.x | (cell.y << 10u) | (cell.z << 20u); }

LANTERN_FUNC uvec4 light_grid_unkey(uint key) {
  return uvec4(key & 1023u, (key >> 10u) & 1023u, (key >> 20u) & 1023u, 0u);
}

// The cell's index in the dense table.
LANTERN_FUNC uint light_grid_index(GpuLightGrid grid, uvec4 cell) {
  return cell.x + grid.dims.x * (cell.y + grid.dims.y * cell.z);
}

// A draw's cell: the neighbour of `cell` (one of 27, x fastest) that u_cell in [0,1) picks;
// false when it lies outside the grid (the draw then gives nothing).
LANTERN_FUNC bool light_grid_neighbour(GpuLightGrid grid, uvec4 cell, float u_cell,
                                       LANTERN_OUT(uvec4) neighbour) {
  uint k = min(uint(u_cell * float(kLightGridNeighbourCells)), kLightGridNeighbourCells - 1u);
  // cell + offset - 1 per axis, in unsigned arithmetic: -1 wraps to a value above any dims.
  neighbour = uvec4(cell.x + k % 3u - 1u, cell.y + (k / 3u) % 3u - 1u, cell.z + k / 9u - 1u, 0u);
  return neighbour.x < grid.dims.x && neighbour.y < grid.dims.y && neighbour.z < grid.dims.z;
}

// The light a draw takes from a cell of `count` lights (> 0): its position in the cell's range.
LANTERN_FUNC uint light_grid_pick(uint count, float u_light) {
  return min(uint(u_light * float(count)), count - 1u);
}

// Whether a light whose cell key is `light_key` lies in one of the 27 cells around `cell`.
LANTERN_FUNC bool light_grid_near(uint light_key, uvec4 cell) {
  if (light_key == kLightGridNoCell) return false;
  uvec4 c = light_grid_unkey(light_key);
  return max(c.x, cell.x) - min(c.x, cell.x) <= 1u && max(c.y, cell.y) - min(c.y, cell.y) <= 1u &&
         max(c.z, cell.z) - min(c.z, cell.z) <= 1u;
}

// Probability that a draw near a point in `cell` gives a light whose cell record is (key, count).
LANTERN_FUNC float light_grid_pdf(uvec2 light_cell, uvec4 cell) {
  if (!light_grid_near(light_cell.x, cell) || light_cell.y == 0u) return 0.0f;
  return 1.0f / (float(kLightGridNeighbourCells) * float(light_cell.y));
}

LANTERN_END_SHARED

#endif
