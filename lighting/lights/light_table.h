// The frame's light list with stable identities. Each emitter has a stable 64-bit id (e.g. the
// entity and the triangle within its mesh); every frame the table takes the scene's emitters
// (only the changed ranges when no light came or went: update_ranges) and derives, from the
// previous frame's ids, the prev->current and current->prev index maps that temporal reuse needs
// when lights appear, move and disappear (RTXDI's PrepareLights idea). Lights are drawn in proportion to their power through two alias tables
// (shared/alias_table.h): the first group (the emissive triangles) and the rest (the analytic
// lights); a group's table is rebuilt only when one of its lights' power changed by more than
// rounding (light_table.cpp: power_moved), so analytic lights that flicker every frame rebuild
// only their own small table, and emitters that merely move rebuild none.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "lighting/lights/alias_table.h"
#include "shared/lights.h"

namespace lantern::lighting {

struct LightEmitter {
  std::uint64_t stable_id = 0;
  gpu::GpuLight light{};
  float power = 0.0f;  // sampling weight: flux (W) for finite lights, a proxy for directional
};

// Lights [first, first + count) of a light list.
struct LightRange {
  std::size_t first = 0;
  std::size_t count = 0;
};

class LightTable {
 public:
  // Replaces the light list with `emitters` (ids must be unique; InputError otherwise), of which
  // the first `first_group` (at most all) form the first sampling group. Returns true when an
  // alias table was rebuilt.
  bool update(std::span<const LightEmitter> emitters, std::size_t first_group);

  // The same light list as the last update (the same ids in the same order, the same groups) of
  // which only the lights in `changed` may have moved or changed power: reads just those
  // (O(changed) instead of O(lights) every frame a few lights flicker or move), rebuilds the
  // table of a group whose power changed, and every light keeps its index. Falls back to
  // update() when the list's size or an id in a changed range differs.
  bool update_ranges(std::span<const LightEmitter> emitters, std::span<const LightRange> changed);

  const std::vector<gpu::GpuLight>& lights() const { return lights_; }
  // Each light's sampling power as its group's table has it (within power_moved's tolerance of
  // the emitters' last powers).
  const std::vector<float>& powers() const { return powers_; }
  const std::vector<std::uint64_t>& stable_ids() const { return ids_; }
  // previous index -> current index (kInvalidLight if the light is gone); sized to last frame.
  const std::vector<std::uint32_t>& previous_to_current() const { return prev_to_cur_; }
  // current index -> previous index (kInvalidLight if the light is new).
  const std::vector<std::uint32_t>& current_to_previous() const { return cur_to_prev_; }

  // Power sampling: both groups' alias entries, one per light (the GPU's scene.light_alias), the
  // first group's size and its share of the power (the draw's first choice); no light can be
  // drawn without power.
  const std::vector<gpu::AliasEntry>& alias_entries() const { return entries_; }
  std::uint32_t first_group_size() const { return static_cast<std::uint32_t>(split_); }
  float first_group_share() const { return first_share_; }
  double total_power() const { return group_power_[0] + group_power_[1]; }
  bool has_power() const { return total_power() > 0.0; }
  // Probability of drawing light i (its power over the total), and a draw from u0, u1 in [0,1):
  // as the GPU draws (alias_group_slot, alias_group_pdf).
  float selection_pdf(std::uint32_t i) const;
  std::uint32_t sample(float u0, float u1) const;
  // Entries the last update rewrote (the rebuilt groups'; empty when none was rebuilt): what an
  // upload of alias_entries() must copy again.
  LightRange alias_rewritten() const { return rewritten_; }
  // Group tables built so far (each group's rebuild counts once).
  std::uint64_t alias_rebuilds() const { return alias_rebuilds_; }

 private:
  std::vector<gpu::GpuLight> lights_;
  std::vector<std::uint64_t> ids_;
  std::vector<float> powers_;
  std::vector<std::uint32_t> prev_to_cur_;
  std::vector<std::uint32_t> cur_to_prev_;
  bool identity_maps_ = false;  // prev_to_cur_ and cur_to_prev_ are the identity over the lights
  std::size_t split_ = 0;       // lights in the first group
  std::vector<gpu::AliasEntry> entries_;
  double group_power_[2] = {0.0, 0.0};
  float first_share_ = 0.0f;
  LightRange rewritten_;
  std::uint64_t alias_rebuilds_ = 0;

  // Same ids in the same order: re-reads the lights in `changed`, keeps every index.
  bool apply_ranges(std::span<const LightEmitter> emitters, std::span<const LightRange> changed);
  void set_identity_maps();
  // Rebuilds the tables of the groups asked for; returns whether any was.
  bool rebuild_groups(bool first, bool second);
};

}  // namespace lantern::lighting
