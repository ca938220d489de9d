// Fixed-step and wall clocks (see clock.h).
#include "engine/core/clock.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "engine/core/error.h"

namespace lantern {

FixedClock::FixedClock(double dt) : dt_(dt) {
  if (!(dt > 0.0) || !std::isfinite(dt)) {
    throw InputError(fmt::format("fixed clock: dt must be a positive finite number of seconds, got {}", dt));
  }
}

FrameTime FixedClock::tick() {
  const std::uint64_t index = started_ ? current_.frame_index + 1 : 0;
  started_ = true;
  // Time is index * dt, not a running sum, so frame N's time does not depend on rounding history.
  current_ = FrameTime{index, dt_, static_cast<double>(index + 1) * dt_};
  return current_;
}

RealClock::RealClock(double max_dt) : max_dt_(max_dt), last_(Steady::now()) {
  if (!(max_dt > 0.0) || !std::isfinite(max_dt)) {
    throw InputError(fmt::format("real clock: max_dt must be a positive finite number of seconds, got {}", max_dt));
  }
}

FrameTime RealClock::tick() {
  const Steady::time_point now = Steady::now();
  const double elapsed = std::chrono::duration<double>(now - last_).count();
  last_ = now;
  const double dt = std::clamp(elapsed, 0.0, max_dt_);
  const std::uint64_t index = started_ ? current_.frame_index + 1 : 0;
  current_ = FrameTime{index, dt, (started_ ? current_.time : 0.0) + dt};
  started_ = true;
  return current_;
}

}  // namespace lantern
