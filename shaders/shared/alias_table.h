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

LANTERN_END_SHARED

#endif
