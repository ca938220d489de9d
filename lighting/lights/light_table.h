// The frame's light list with stable identities. Each emitter has a stable 64-bit id (e.g. the
// entity and the triangle within its mesh); every frame the table is rebuilt from the scene's
// emitters and derives, from the previous frame's ids, the prev->current and current->prev index
// maps that temporal reuse needs when lights appear, move and disappear (RTXDI's PrepareLights
// idea). The power alias table is rebuilt only when some emitter's power changed.
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
  // Replaces the light list with `emitters` (ids must be unique; InputError otherwise).
  // Returns true when the alias table was rebuilt.
  bool update(std::span<const LightEmitter> emitters);

  // The same light list as the last update (the same ids in the same order) of which only the
  // lights in `changed` may have moved or changed power: reads just those (O(changed) instead of
  // O(lights) every frame a few lights flicker or move; the alias table is still rebuilt when a
  // power changed), and every light keeps its index. Falls back to update() when the list's size
  // or an id in a changed range differs.
  bool update_ranges(std::span<const LightEmitter> emitters, std::span<const LightRange> changed);

  const std::vector<gpu::GpuLight>& lights() const { return lights_; }
  const std::vector<std::uint64_t>& stable_ids() const { return ids_; }
  // previous index -> current index (kInvalidLight if the light is gone); sized to last frame.
  const std::vector<std::uint32_t>& previous_to_current() const { return prev_to_cur_; }
  // current index -> previous index (kInvalidLight if the light is new).
  const std::vector<std::uint32_t>& current_to_previous() const { return cur_to_prev_; }
  // Power alias table over the current lights; empty when there are no lights or no power.
  const AliasTable& alias_table() const { return alias_; }
  bool has_power() const { return alias_.size() != 0; }
  std::uint64_t alias_rebuilds() const { return alias_rebuilds_; }

 private:
  std::vector<gpu::GpuLight> lights_;
  std::vector<std::uint64_t> ids_;
  std::vector<float> powers_;
  std::vector<std::uint32_t> prev_to_cur_;
  std::vector<std::uint32_t> cur_to_prev_;
  bool identity_maps_ = false;  // prev_to_cur_ and cur_to_prev_ are the identity over the lights
  AliasTable alias_;
  std::uint64_t alias_rebuilds_ = 0;

  // Same ids in the same order: re-reads the lights in `changed`, keeps every index.
  bool apply_ranges(std::span<const LightEmitter> emitters, std::span<const LightRange> changed);
  void set_identity_maps();
  bool rebuild_alias();
};

}  // namespace lantern::lighting
