// Reservoir ping-pong plan: see reservoir_buffers.h.
#include "lighting/restir/reservoir_buffers.h"

#include <fmt/format.h>

namespace lantern::lighting {

std::vector<ReservoirStep> ReservoirBuffers::plan(const Frame& frame) {
  std::vector<ReservoirStep> steps;
  const std::uint32_t resamplers = 1 + (frame.temporal ? 1 : 0) + frame.spatial_passes;
  std::uint32_t index = 0;
  ReservoirBuffer current = ReservoirBuffer::None;
  // The k-th resampling pass writes Final if it is the last one, else the scratch buffer its
  // input is not in (A first).
  auto output = [&]() {
    ++index;
    if (index == resamplers) return ReservoirBuffer::Final;
    return current == ReservoirBuffer::ScratchA ? ReservoirBuffer::ScratchB
                                                : ReservoirBuffer::ScratchA;
  };

  ReservoirStep initial;
  initial.stage = ReservoirStage::Initial;
  initial.write = output();
  current = initial.write;
  steps.push_back(initial);

  if (frame.temporal) {
    ReservoirStep temporal;
    temporal.stage = ReservoirStage::Temporal;
    temporal.read = current;
    temporal.history = frame.history_valid ? ReservoirBuffer::History : ReservoirBuffer::None;
    temporal.write = output();
    current = temporal.write;
    steps.push_back(temporal);
  }
  for (std::uint32_t i = 0; i < frame.spatial_passes; ++i) {
    ReservoirStep spatial;
    spatial.stage = ReservoirStage::Spatial;
    spatial.spatial_index = i;
    spatial.read = current;
    spatial.write = output();
    current = spatial.write;
    steps.push_back(spatial);
  }
  ReservoirStep shade;
  shade.stage = ReservoirStage::Shade;
  shade.read = current;
  steps.push_back(shade);
  return steps;
}

std::vector<ReservoirStep> ReservoirBuffers::next_frame(Frame frame) {
  frame.history_valid = frame.history_valid && final_written_;
  final_written_ = true;  // every plan ends by writing Final
  return plan(frame);
}

const char* reservoir_buffer_name(ReservoirBuffer buffer) {
  switch (buffer) {
    case ReservoirBuffer::None:
      return "-";
    case ReservoirBuffer::ScratchA:
      return "a";
    case ReservoirBuffer::ScratchB:
      return "b";
    case ReservoirBuffer::Final:
      return "final";
    case ReservoirBuffer::History:
      return "history";
  }
  return "?";
}

const char* reservoir_stage_name(ReservoirStage stage) {
  switch (stage) {
    case ReservoirStage::Initial:
      return "restir.initial";
    case ReservoirStage::Temporal:
      return "restir.temporal";
    case ReservoirStage::Spatial:
      return "restir.spatial";
    case ReservoirStage::Shade:
      return "restir.shade";
  }
  return "?";
}

std::string describe(const std::vector<ReservoirStep>& steps) {
  std::string out;
  for (const ReservoirStep& s : steps) {
    if (!out.empty()) out += "; ";
    out += reservoir_stage_name(s.stage);
    if (s.stage == ReservoirStage::Spatial) out += fmt::format("[{}]", s.spatial_index);
    out += fmt::format(": {}", reservoir_buffer_name(s.read));
    if (s.history != ReservoirBuffer::None)
      out += fmt::format(" + {}", reservoir_buffer_name(s.history));
    if (s.stage != ReservoirStage::Shade) out += fmt::format(" -> {}", reservoir_buffer_name(s.write));
  }
  return out;
}

}  // namespace lantern::lighting
