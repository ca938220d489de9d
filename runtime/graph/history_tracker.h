// The one CPU object that decides, per frame, which of a history resource's two physical slots
// is written this frame and whether last frame's slot holds valid contents. History is invalid
// on the first frame, after the resource's description changed (resize), after
// invalidate_all() (camera cut), and when the resource was not written in the previous frame.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <variant>

#include "runtime/graph/resource_desc.h"

namespace lantern::runtime::graph {

using HistoryDesc = std::variant<BufferDesc, ImageDesc>;

class HistoryTracker {
 public:
  struct Slots {
    uint32_t write = 0;       // physical slot this frame writes
    uint32_t read = 0;        // physical slot holding last frame's contents
    bool read_valid = false;  // false: the pass gets no history and must cope
    bool recreated = false;   // description changed: physical slots must be (re)allocated
  };

  // Starts frame `frame_index + 1`; declarations below belong to it.
  void begin_frame() { ++frame_; }
  [[nodiscard]] uint64_t frame() const { return frame_; }

  // Declares the history resource `name` for the current frame.
  Slots declare(std::string_view name, const HistoryDesc& desc);
  // Records that `name` was written this frame (its write slot now holds the newest contents).
  void mark_written(std::string_view name);
  // Drops every history's contents (camera cut). Slots and their sync state stay.
  void invalidate_all();

  // Last known synchronisation state of a physical slot, carried across frames for barriers.
  [[nodiscard]] AccessState slot_state(std::string_view name, uint32_t slot) const;
  void set_slot_state(std::string_view name, uint32_t slot, const AccessState& state);

 private:
  struct Entry {
    HistoryDesc desc;
    int32_t latest_slot = -1;  // slot with the newest contents, -1 = none
    uint32_t write_slot = 0;   // slot the current frame writes
    uint64_t written_frame = 0;
    uint64_t declared_frame = 0;
    AccessState state[2];
  };
  std::map<std::string, Entry, std::less<>> entries_;
  uint64_t frame_ = 0;
};

}  // namespace lantern::runtime::graph
