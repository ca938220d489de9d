// HistoryTracker: ping-pong slot choice and validity of last frame's contents.
#include "runtime/graph/history_tracker.h"

#include <fmt/format.h>

#include "engine/core/error.h"

namespace lantern::runtime::graph {

HistoryTracker::Slots HistoryTracker::declare(std::string_view name, const HistoryDesc& desc) {
  auto it = entries_.find(name);
  Slots slots;
  if (it == entries_.end() || !(it->second.desc == desc)) {
    // First sight or resize: fresh slots, nothing to read.
    Entry entry;
    entry.desc = desc;
    entry.declared_frame = frame_;
    entries_.insert_or_assign(std::string(name), entry);
    slots.recreated = true;
    return slots;
  }
  Entry& e = it->second;
  if (e.declared_frame == frame_)
    throw RuntimeError(fmt::format("render graph: history resource '{}' declared twice in frame {}",
                                   name, frame_));
  e.declared_frame = frame_;
  const bool has_contents = e.latest_slot >= 0;
  slots.read = has_contents ? static_cast<uint32_t>(e.latest_slot) : 0;
  slots.write = has_contents ? 1 - slots.read : 0;
  slots.read_valid = has_contents && e.written_frame + 1 == frame_;
  e.write_slot = slots.write;
  return slots;
}

void HistoryTracker::mark_written(std::string_view name) {
  auto it = entries_.find(name);
  if (it == entries_.end()) return;
  Entry& e = it->second;
  e.latest_slot = static_cast<int32_t>(e.write_slot);
  e.written_frame = frame_;
}

void HistoryTracker::invalidate_all() {
  for (auto& [name, e] : entries_) e.latest_slot = -1;
}

AccessState HistoryTracker::slot_state(std::string_view name, uint32_t slot) const {
  auto it = entries_.find(name);
  return it == entries_.end() || slot > 1 ? AccessState{} : it->second.state[slot];
}

void HistoryTracker::set_slot_state(std::string_view name, uint32_t slot,
                                    const AccessState& state) {
  auto it = entries_.find(name);
  if (it != entries_.end() && slot <= 1) it->second.state[slot] = state;
}

}  // namespace lantern::runtime::graph
