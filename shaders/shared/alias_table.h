// Walker/Vose alias table: O(1) sampling of an index proportional to a weight (light power).
// Built on the CPU (lighting/lights/alias_table.cpp), sampled identically on CPU and GPU.
#ifndef LANTERN_SHARED_ALIAS_TABLE_H
#define LANTERN_SHARED_ALIAS_TABLE_H

#include "shared/lang.h"

LANTERN_BEGIN_SHARED

struct AliasEntry {
  float threshold;  // keep this slot's own index when u < threshold, else take `alias`
  uint alias;       // the other index sharing this slot
  float pdf;        // probability of selecting this slot's own index (weight / total)
  uint pad0;
};
LANTERN_STATIC_SIZE(AliasEntry, 16);

// Given the slot drawn from u0 (alias_slot), keeps its own index or takes its alias by u1.
LANTERN_FUNC uint alias_select(float u1, AliasEntry entry, uint slot) {
  return u1 < entry.threshold ? slot : entry.alias;
}

// Slot index for u0 in [0,1): clamped so that u0 close to 1 never reads past the end.
LANTERN_FUNC uint alias_slot(uint count, float u0) {
  return min(uint(u0 * float(count)), count - 1u);
}

// The lights are drawn in two groups, each from its own alias table over its own powers
// (lighting/lights/light_table.h), stored one after the other: lights [0, split) (the emissive
// triangles, whose power rarely changes) and [split, count) (the analytic lights, which flicker),
// so a frame in which analytic lights flicker rebuilds only their small table. A draw picks the
// first group with probability first_share (its share of the total power; exactly 0 or 1 when a
// group has none), then a slot of that group's table; entries' alias indices are absolute and
// their pdf relative to their group. Each light is drawn in proportion to its power, as from one
// table over all of them.

// The slot u0 (in [0,1)) draws: the group by u0, then u0 rescaled within it.
LANTERN_FUNC uint alias_group_slot(uint count, uint split, float first_share, float u0) {
  if (u0 < first_share) {
    return alias_slot(split, u0 / first_share);
  }
  return split + alias_slot(count - split, (u0 - first_share) / (1.0f - first_share));
}

// Probability of drawing light `index`, whose entry holds the group-relative entry_pdf.
LANTERN_FUNC float alias_group_pdf(float entry_pdf, uint index, uint split, float first_share) {
  return entry_pdf * (index < split ? first_share : 1.0f - first_share);
}

LANTERN_END_SHARED

#endif
