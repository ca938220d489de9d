// The one CPU object that decides which reservoir buffer each ReSTIR pass reads and writes in a
// frame. Chain: restir.initial -> restir.temporal (also reads last frame's final reservoirs) ->
// restir.spatial x N -> restir.shade; the last pass that resamples writes the Final buffer, a
// render-graph history resource, so it becomes next frame's temporal input. Two transient
// buffers (A, B) ping-pong between the other passes. Each is a separate graph resource, so the
// graph sees (and orders) every read-after-write; no pass reads and writes one buffer.
//
// Pure logic, no Vulkan: RestirIntegrator maps the ids to graph handles.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace lantern::lighting {

enum class ReservoirBuffer : std::uint8_t {
  None,     // no input (initial) / no history
  ScratchA,  // transient "restir.reservoirs.a"
  ScratchB,  // transient "restir.reservoirs.b"
  Final,    // history resource "restir.reservoirs": this frame's final reservoirs
  History,  // last frame's Final (HistoryPrevious)
};

enum class ReservoirStage : std::uint8_t { Initial, Temporal, Spatial, Shade };

struct ReservoirStep {
  ReservoirStage stage = ReservoirStage::Initial;
  std::uint32_t spatial_index = 0;                 // Spatial: which pass
  ReservoirBuffer read = ReservoirBuffer::None;    // reservoirs resampled / shaded
  ReservoirBuffer history = ReservoirBuffer::None;  // Temporal: History, or None (no reuse)
  ReservoirBuffer write = ReservoirBuffer::None;   // None for Shade
};

class ReservoirBuffers {
 public:
  struct Frame {
    bool temporal = true;             // the temporal pass runs
    std::uint32_t spatial_passes = 0;
    bool history_valid = false;       // last frame wrote Final and no cut/resize happened since
  };

  // The steps of one frame in execution order. A temporal pass without valid history still runs
  // (it passes its input through and marks every pixel "no history"), so the chain's shape only
  // depends on the settings.
  static std::vector<ReservoirStep> plan(const Frame& frame);

  // Per-frame bookkeeping: call once per frame; returns plan() with history_valid forced false
  // when last frame did not write Final (first frame, or temporal reuse was switched on now).
  std::vector<ReservoirStep> next_frame(Frame frame);
  void reset() { final_written_ = false; }

 private:
  bool final_written_ = false;
};

const char* reservoir_buffer_name(ReservoirBuffer buffer);
const char* reservoir_stage_name(ReservoirStage stage);
// "restir.initial: - -> a; restir.temporal: a + history -> final; restir.shade: final" (tests/logs).
std::string describe(const std::vector<ReservoirStep>& steps);

}  // namespace lantern::lighting
