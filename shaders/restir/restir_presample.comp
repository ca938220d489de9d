// restir.presample: light presampling (shared/restir.h). Entry e of tile t is a light drawn from
// the power alias table with its own random numbers, stored with a copy of its record, its
// density (selection pdf x point density) and its light grid record (light_cells: the balance
// heuristic's grid density), for restir.initial's light candidates.
// Reads: frame constants, lights, alias table, light_cells.
// Writes: presampled_lights (push.presample_tiles x kRestirPresampleTileSize entries).
// History: none.
// Dispatch: one invocation per entry (64 per workgroup).
#version 460
#extension GL_GOOGLE_include_directive : require

#include "restir/restir_common.glsl"
#include "shared/alias_table.h"

layout(std430, binding = PASS_BINDING(0)) writeonly buffer PresampledOut {
  PresampledLight e[];
} presampled_lights;

void main() {
  uint entry = gl_WorkGroupID.x * kPixelGroupThreads + gl_LocalInvocationIndex;
  uint light_count = restir_light_count();
  if (entry >= push.presample_tiles * kRestirPresampleTileSize || light_count == 0u) return;
  uint rng = frame_rng(uvec2(entry % kRestirPresampleTileSize, entry / kRestirPresampleTileSize),
                       kRestirRngPresample);
  float u0 = rng_next_float(rng);
  float u1 = rng_next_float(rng);
  uint index = scene_light_sample(u0, u1);
  PresampledLight p;
  p.light = scene_light(index);
  p.index = index;
  p.pdf = scene_light_selection_pdf(index) * light_eval_point_pdf(p.light);
  p.grid_cell = light_cells.c[index];
  presampled_lights.e[entry] = p;
}
