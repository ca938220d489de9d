// The bench calibration workload runs, is timed, and is repeatable enough to scale budgets.
#include "runtime/perf/calibration_workload.h"

#include <gtest/gtest.h>

#include "runtime/gpu/shader_library.h"
#include "gpu_test_support.h"

namespace lantern::runtime {
namespace {

using CalibrationTest = test::GpuTest;

TEST_F(CalibrationTest, RunsAndReportsGpuTime) {
  ShaderLibrary shaders;
  CalibrationWorkload workload(device, shaders);
  const double a = workload.run_ms();
  const double b = workload.run_ms();
  EXPECT_GT(a, 0.0);
  EXPECT_GT(b, 0.0);
  EXPECT_LT(a, 10000.0);
}

}  // namespace
}  // namespace lantern::runtime
