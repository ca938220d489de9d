// The light grid: the lights binned by where they are, in a uniform grid of world-space cells
// over the lights' bounds (built on the CPU by lighting/lights/light_grid.cpp, read by
// restir.initial's grid candidates: a light drawn near the shading point, whose density any
// light's own cell record gives back in O(1) once the 27 cells around the point are weighed).
// A light's place: a triangle's centroid, a point or spot light's position; a directional light
// has none (it is in no cell, and the grid never draws it).
// Drawing near a surface point x with normal n: one of the 3x3x3 cells around x's cell in
// proportion to light_grid_weight (the cell's power over its squared distance from x; none for an
// empty cell, one outside the grid or one wholly behind the surface), then one light of that cell
// by the cell's alias table (light_grid_pick) over half its power plus half the cell's mean power
// (lighting/lights/light_grid.cpp). Light l is drawn with probability w(l's cell) / W x q(l), W
// the 27 weights' sum and q(l) l's share of its cell's alias weights (its light_cells record),
// where l's cell is one of the 27 (light_grid_pdf), else 0: a light that only the other
// strategies reach, which stays unbiased while they cover it (restir.initial's light candidates
// cover every light). The cells' powers are those of the build (a flickering light
// keeps its cell's power until the grid is built again): the density the draw uses is the one
// every candidate is weighed with, whatever the light does now.
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
// then y, then z; kLightGridCellWords words each: GpuLightGridCell) and the cell-ordered light
// list (kLightGridEntryWords words each: GpuLightGridEntry). scene.light_cells holds per light
// (its cell's key or kLightGridNoCell, the bits of its share q of its cell's alias weights).
// One cell of the dense table: its lights' range in the grid's list and their power.
struct GpuLightGridCell {
  uint first;   // first of its lights in the grid's light list
  uint count;   // its lights (0: an empty cell)
  float power;  // their sampling power summed (LightTable's, at the build)
};
LANTERN_STATIC_SIZE(GpuLightGridCell, 12);
LANTERN_CONST uint kLightGridCellWords = 3u;

// One slot of a cell's alias table over its lights (by power), in the cell-ordered light list.
struct GpuLightGridEntry {
  uint light;       // the slot's own light index
  float threshold;  // keep `light` when the slot's u < threshold, else take `alias`
  uint alias;       // the light index that shares the slot
};
LANTERN_STATIC_SIZE(GpuLightGridEntry, 12);
LANTERN_CONST uint kLightGridEntryWords = 3u;

// Words of the dense table after the header: where the cell-ordered light list starts.
LANTERN_FUNC uint light_grid_cell_words(GpuLightGrid grid) {
  return kLightGridCellWords * grid.dims.x * grid.dims.y * grid.dims.z;
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

// Neighbour k (0..26, x fastest) of `cell`: cell + (k % 3, k / 3 % 3, k / 9) - 1 per axis; false
// when it lies outside the grid.
LANTERN_FUNC bool light_grid_neighbour(GpuLightGrid grid, uvec4 cell, uint k,
                                       LANTERN_OUT(uvec4) neighbour) {
  // In unsigned arithmetic -1 wraps to a value above any dims.
  neighbour = uvec4(cell.x + k % 3u - 1u, cell.y + (k / 3u) % 3u - 1u, cell.z + k / 9u - 1u, 0u);
  return neighbour.x < grid.dims.x && neighbour.y < grid.dims.y && neighbour.z < grid.dims.z;
}

// The largest cell weight: 27 of them still sum to a finite number, whatever the powers and the
// cell edge (a weight that overflowed would make every density NaN).
LANTERN_CONST float kLightGridMaxWeight = 1e36f;

// The weight a draw near x (geometric normal n) gives a neighbour cell whose lights carry `power`:
// power over the squared distance from x to the cell's centre, that distance at least half an
// edge (x's own cell and its neighbours are then alike within ~4x), at most kLightGridMaxWeight;
// 0 where the whole cell lies behind the plane of x (its centre more than half a diagonal below
// it).
LANTERN_FUNC float light_grid_weight(GpuLightGrid grid, uvec4 neighbour, float power, vec3 x,
                                     vec3 n) {
  float edge = grid.origin_cell.w;
  vec3 centre = vec3(grid.origin_cell) +
                (vec3(float(neighbour.x), float(neighbour.y), float(neighbour.z)) + 0.5f) * edge;
  vec3 d = centre - x;
  if (dot(d, n) < -0.8660254f * edge) return 0.0f;
  return min(power / max(dot(d, d), 0.25f * edge * edge), kLightGridMaxWeight);
}

// The light a draw takes from a cell of `count` lights (> 0) by u_light in [0,1): the slot it
// lands in (its position in the cell's range), then that slot's own light or its alias by where
// in the slot u_light lies.
LANTERN_FUNC uint light_grid_pick(GpuLightGridEntry slot_entry, float slot_u) {
  return slot_u < slot_entry.threshold ? slot_entry.light : slot_entry.alias;
}
LANTERN_FUNC uint light_grid_slot(uint count, float u_light, LANTERN_OUT(float) slot_u) {
  float scaled = u_light * float(count);
  uint slot = min(uint(scaled), count - 1u);
  slot_u = clamp(scaled - float(slot), 0.0f, 1.0f);
  return slot;
}

// Which of the 27 cells around `cell` holds a light whose cell key is `light_key`
// (light_grid_neighbour's k), kLightGridNeighbourCells where none does.
LANTERN_FUNC uint light_grid_near_index(uint light_key, uvec4 cell) {
  if (light_key == kLightGridNoCell) return kLightGridNeighbourCells;
  uvec4 c = light_grid_unkey(light_key);
  // c - cell + 1 per axis, in unsigned arithmetic: a cell further than 1 away reads above 2.
  uvec4 o = uvec4(c.x + 1u - cell.x, c.y + 1u - cell.y, c.z + 1u - cell.z, 0u);
  if (o.x > 2u || o.y > 2u || o.z > 2u) return kLightGridNeighbourCells;
  return o.x + 3u * o.y + 9u * o.z;
}

// Probability that a draw gives a light whose share of its cell's alias weights is `share` (its
// light_cells record's second word), the cell weighing `cell_weight` among weights summing to
// `total` (0 where any of them is 0).
LANTERN_FUNC float light_grid_pdf(float cell_weight, float total, float share) {
  if (!(cell_weight > 0.0f) || !(total > 0.0f) || !(share > 0.0f)) return 0.0f;
  return cell_weight / total * share;
}

LANTERN_END_SHARED

#endif
