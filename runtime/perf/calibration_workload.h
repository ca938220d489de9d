// The calibration workload of `lantern bench` (shaders/perf/perf_calibration.comp): a fixed GPU
// job timed in the same run as the frames, so budgets can be stated as multiples of it and stay
// meaningful on a noisy shared machine where everything slows down together.
#pragma once

#include "runtime/gpu/buffer.h"
#include "runtime/gpu/compute_pipeline.h"

namespace lantern::runtime {

class Device;
class ShaderLibrary;

class CalibrationWorkload {
 public:
  CalibrationWorkload(Device& device, ShaderLibrary& shaders);
  // Runs the workload once (its own submission) and returns its GPU milliseconds.
  double run_ms();

 private:
  Device& device_;
  ComputePipeline pipeline_;
  Buffer table_;
  Buffer result_;
};

}  // namespace lantern::runtime
