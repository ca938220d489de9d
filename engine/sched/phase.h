// The phases of a frame, in execution order. Each phase is a barrier: every system of one phase
// finishes before any system of the next starts.
#pragma once

#include <cstddef>
#include <string_view>

namespace lantern {

enum class Phase : unsigned char {
  Input,      // read devices / scripted input
  Simulate,   // behaviours, animation, camera paths
  Transform,  // propagate and finalise world transforms
  Extract,    // read the world, build the immutable frame snapshot
  Render,     // record the frame's render graph from the snapshot
};

inline constexpr std::size_t kPhaseCount = 5;

constexpr std::string_view phase_name(Phase p) {
  switch (p) {
    case Phase::Input: return "Input";
    case Phase::Simulate: return "Simulate";
    case Phase::Transform: return "Transform";
    case Phase::Extract: return "Extract";
    case Phase::Render: return "Render";
  }
  return "?";
}

}  // namespace lantern
