#include "lighting/lights/light_table.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <unordered_map>

#include "engine/core/error.h"

namespace lantern::lighting {
namespace {

// Whether a light's power `now` differs from the power its group's table was built with by more
// than the rounding of its own geometry: a rotating emitter's triangle areas, computed from
// world-space vertices, move by up to 1.2e-4 of themselves from frame to frame (night_market's
// spinners: thin 1 x 0.05 faces 10-20 m from the origin), which would rebuild (and upload) the
// triangles' whole table every frame for nothing. Sampling from a table built with powers within
// this tolerance stays unbiased (every estimator divides by the table's own pdf, and a pdf is > 0
// exactly where the power is); only its match to the true powers is off by at most this much. A
// power that becomes zero, non-zero or non-finite always counts (the last is refused by the
// rebuild).
constexpr float kPowerTolerance = 1e-3f;

bool power_moved(float built, float now) {
  if (!std::isfinite(now) || (built > 0.0f) != (now > 0.0f)) return true;
  return std::abs(now - built) > kPowerTolerance * built;
}

}  // namespace

bool LightTable::update(std::span<const LightEmitter> emitters, std::size_t first_group) {
  first_group = std::min(first_group, emitters.size());
  // Fast path (every frame of a level whose lights only move or change power): the same ids in
  // the same order map every light to itself, no hashing needed.
  if (emitters.size() == ids_.size() && !emitters.empty() && first_group == split_) {
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

  // A group whose powers all stay within power_moved's tolerance keeps the powers its table was
  // built with (so a slow drift is caught once it adds up), and its table.
  const bool regrouped = first_group != split_ || emitters.size() != ids_.size();
  bool group_changed[2] = {regrouped, regrouped};
  for (std::size_t i = 0; !regrouped && i < powers.size(); ++i)
    group_changed[i < first_group ? 0 : 1] |= power_moved(powers_[i], powers[i]);
  for (std::size_t i = 0; i < powers.size(); ++i)
    if (!group_changed[i < first_group ? 0 : 1]) powers[i] = powers_[i];
  ids_ = std::move(ids);
  lights_ = std::move(lights);
  powers_ = std::move(powers);
  cur_to_prev_ = std::move(cur_to_prev);
  prev_to_cur_ = std::move(prev_to_cur);
  identity_maps_ = false;
  split_ = first_group;
  entries_.resize(ids_.size());
  return rebuild_groups(group_changed[0], group_changed[1]);
}

bool LightTable::update_ranges(std::span<const LightEmitter> emitters,
                               std::span<const LightRange> changed) {
  bool same = emitters.size() == ids_.size() && !emitters.empty();
  for (const LightRange& r : changed) {
    same = same && r.first <= emitters.size() && r.count <= emitters.size() - r.first;
    for (std::size_t i = r.first; same && i < r.first + r.count; ++i)
      same = emitters[i].stable_id == ids_[i];
  }
  return same ? apply_ranges(emitters, changed) : update(emitters, split_);
}

bool LightTable::apply_ranges(std::span<const LightEmitter> emitters,
                              std::span<const LightRange> changed) {
  bool group_changed[2] = {false, false};
  for (const LightRange& r : changed) {
    for (std::size_t i = r.first; i < r.first + r.count; ++i) {
      lights_[i] = emitters[i].light;
      group_changed[i < split_ ? 0 : 1] |= power_moved(powers_[i], emitters[i].power);
    }
  }
  for (const LightRange& r : changed)
    for (std::size_t i = r.first; i < r.first + r.count; ++i)
      if (group_changed[i < split_ ? 0 : 1]) powers_[i] = emitters[i].power;
  set_identity_maps();
  return rebuild_groups(group_changed[0], group_changed[1]);
}

void LightTable::set_identity_maps() {
  if (identity_maps_ && prev_to_cur_.size() == ids_.size()) return;
  prev_to_cur_.resize(ids_.size());
  cur_to_prev_.resize(ids_.size());
  for (std::uint32_t i = 0; i < ids_.size(); ++i) prev_to_cur_[i] = cur_to_prev_[i] = i;
  identity_maps_ = true;
}

bool LightTable::rebuild_groups(bool first, bool second) {
  rewritten_ = {};
  const std::size_t bounds[3] = {0, split_, ids_.size()};
  for (int g = 0; g < 2; ++g) {
    if (!(g == 0 ? first : second)) continue;
    const std::size_t begin = bounds[g];
    const std::size_t end = bounds[g + 1];
    double total = 0.0;
    for (std::size_t i = begin; i < end; ++i) {
      if (!std::isfinite(powers_[i]) || powers_[i] < 0.0f)
        throw InputError(fmt::format("light table: light {} has power {} (must be finite and >= 0)",
                                     i, powers_[i]));
      total += powers_[i];
    }
    group_power_[g] = total;
    if (total > 0.0) {
      // The group's own table, its alias indices moved to the group's place in the list.
      const AliasTable table(std::span<const float>(powers_).subspan(begin, end - begin));
      for (std::size_t i = begin; i < end; ++i) {
        entries_[i] = table.entries()[i - begin];
        entries_[i].alias += static_cast<std::uint32_t>(begin);
      }
    } else {
      for (std::size_t i = begin; i < end; ++i)
        entries_[i] = {1.0f, static_cast<std::uint32_t>(i), 0.0f, 0u};
    }
    ++alias_rebuilds_;
  }
  if (!first && !second) return false;
  // The groups lie side by side: the rewritten entries run from the first rebuilt to the last.
  const std::size_t from = first ? 0 : split_;
  rewritten_ = {from, (second ? ids_.size() : split_) - from};
  // The first group's share, exactly 0 or 1 when a group has no power (so a draw never lands in
  // an empty or powerless group), else kept a float step inside (0, 1): a group whose share
  // rounds to 0 would never be drawn although its pdf says it is.
  const double total = total_power();
  if (!(group_power_[1] > 0.0)) {
    first_share_ = total > 0.0 ? 1.0f : 0.0f;
  } else if (!(group_power_[0] > 0.0)) {
    first_share_ = 0.0f;
  } else {
    constexpr float kStep = 1.0f / 16777216.0f;  // 2^-24
    first_share_ = std::clamp(static_cast<float>(group_power_[0] / total), kStep, 1.0f - kStep);
  }
  return true;
}

float LightTable::selection_pdf(std::uint32_t i) const {
  return gpu::alias_group_pdf(entries_[i].pdf, i, static_cast<std::uint32_t>(split_), first_share_);
}

std::uint32_t LightTable::sample(float u0, float u1) const {
  const std::uint32_t slot =
      gpu::alias_group_slot(static_cast<std::uint32_t>(entries_.size()),
                            static_cast<std::uint32_t>(split_), first_share_, u0);
  return gpu::alias_select(u1, entries_[slot], slot);
}

}  // namespace lantern::lighting
