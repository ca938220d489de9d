#include "lighting/lights/light_table.h"

#include <fmt/format.h>

#include <array>
#include <unordered_map>

#include "engine/core/error.h"

namespace lantern::lighting {

bool LightTable::update(std::span<const LightEmitter> emitters) {
  // Fast path (every frame of a level whose lights only move or change power): the same ids in
  // the same order map every light to itself, no hashing needed.
  if (emitters.size() == ids_.size() && !emitters.empty()) {
    bool same = true;
    for (std::size_t i = 0; i < emitters.size() && same; ++i)
      same = emitters[i].stable_id == ids_[i];
    if (same) return apply_ranges(emitters, std::array{LightRange{0, emitters.size()}});
  }
  // Index the previous frame's ids, then map each current emitter to its previous slot.
  std::unordered_map<std::uint64_t, std::uint32_t> previous;
  previous.reserve(ids_.size());
  for (std::uint32_t i = 0; i < ids_.size(); ++i) previous.emplace(ids_[i], i);

  std::vector<std::uint64_t> ids(emitters.size());
  std::vector<gpu::GpuLight> lights(emitters.size());
  std::vector<float> powers(emitters.size());
  std::vector<std::uint32_t> cur_to_prev(emitters.size(), gpu::kInvalidLight);
  std::vector<std::uint32_t> prev_to_cur(ids_.size(), gpu::kInvalidLight);
  std::unordered_map<std::uint64_t, std::uint32_t> seen;
  seen.reserve(emitters.size());
  for (std::uint32_t i = 0; i < emitters.size(); ++i) {
    const LightEmitter& e = emitters[i];
    if (!seen.emplace(e.stable_id, i).second)
      throw InputError(fmt::format("light table: stable id {:#x} appears twice (lights {} and {})",
                                   e.stable_id, seen[e.stable_id], i));
    ids[i] = e.stable_id;
    lights[i] = e.light;
    powers[i] = e.power;
    if (auto it = previous.find(e.stable_id); it != previous.end()) {
      cur_to_prev[i] = it->second;
      prev_to_cur[it->second] = i;
    }
  }

  const bool power_changed = powers != powers_;
  ids_ = std::move(ids);
  lights_ = std::move(lights);
  powers_ = std::move(powers);
  cur_to_prev_ = std::move(cur_to_prev);
  prev_to_cur_ = std::move(prev_to_cur);
  identity_maps_ = false;
  return power_changed && rebuild_alias();
}

bool LightTable::update_ranges(std::span<const LightEmitter> emitters,
                               std::span<const LightRange> changed) {
  bool same = emitters.size() == ids_.size() && !emitters.empty();
  for (const LightRange& r : changed) {
    same = same && r.first <= emitters.size() && r.count <= emitters.size() - r.first;
    for (std::size_t i = r.first; same && i < r.first + r.count; ++i)
      same = emitters[i].stable_id == ids_[i];
  }
  return same ? apply_ranges(emitters, changed) : update(emitters);
}

bool LightTable::apply_ranges(std::span<const LightEmitter> emitters,
                              std::span<const LightRange> changed) {
  bool power_changed = false;
  for (const LightRange& r : changed) {
    for (std::size_t i = r.first; i < r.first + r.count; ++i) {
      lights_[i] = emitters[i].light;
      power_changed = power_changed || powers_[i] != emitters[i].power;
      powers_[i] = emitters[i].power;
    }
  }
  set_identity_maps();
  return power_changed && rebuild_alias();
}

void LightTable::set_identity_maps() {
  if (identity_maps_ && prev_to_cur_.size() == ids_.size()) return;
  prev_to_cur_.resize(ids_.size());
  cur_to_prev_.resize(ids_.size());
  for (std::uint32_t i = 0; i < ids_.size(); ++i) prev_to_cur_[i] = cur_to_prev_[i] = i;
  identity_maps_ = true;
}

bool LightTable::rebuild_alias() {
  double total = 0.0;
  for (float p : powers_) total += p;
  alias_ = total > 0.0 ? AliasTable(powers_) : AliasTable();
  ++alias_rebuilds_;
  return true;
}

}  // namespace lantern::lighting
