// Frame clocks behind one interface. FixedClock: every frame lasts exactly `dt` (captures,
// benchmarks, tests: deterministic). RealClock: wall time, with dt clamped so a stall (debugger,
// window drag) does not make the simulation jump.
#pragma once

#include <chrono>
#include <cstdint>

namespace lantern {

struct FrameTime {
  std::uint64_t frame_index = 0;  // 0 for the first frame
  double dt = 0.0;                // seconds simulated by this frame
  double time = 0.0;              // seconds since the start, at the end of this frame
};

class Clock {
 public:
  virtual ~Clock() = default;
  // Advances one frame and returns its time.
  virtual FrameTime tick() = 0;
  // The last value tick() returned (frame_index 0, dt 0 before the first tick).
  const FrameTime& current() const { return current_; }

 protected:
  FrameTime current_;
  bool started_ = false;
};

class FixedClock final : public Clock {
 public:
  // `dt` in seconds; must be positive and finite (throws InputError otherwise).
  explicit FixedClock(double dt);
  FrameTime tick() override;
  double dt() const { return dt_; }

 private:
  double dt_;
};

class RealClock final : public Clock {
 public:
  // `max_dt` in seconds: the largest step one frame may take.
  explicit RealClock(double max_dt = 0.1);
  FrameTime tick() override;

 private:
  using Steady = std::chrono::steady_clock;
  double max_dt_;
  Steady::time_point last_;
};

}  // namespace lantern
