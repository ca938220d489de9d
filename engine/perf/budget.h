// Frame-time budgets (`lantern bench --budget FILE`): limits for the frame and for named passes,
// either relative to a calibration workload timed in the same run (robust on noisy shared
// machines: both slow down together) or in absolute milliseconds for a named device.
//
//   {
//     "level": "cornell_lights", "size": [320, 180], "integrator": "restir", "preset": "balanced",
//     "statistic": "median",
//     "relative": {"frame": 8.0, "passes": {"restir.shade": 2.5}},
//     "absolute": [{"device": "llvmpipe", "frame": 40.0, "passes": {"gbuffer": 5.0}}]
//   }
//
// "relative" limits are multiples of the calibration workload's median GPU ms; an "absolute"
// entry applies when its "device" text occurs in the device name. level/size/integrator/preset
// are optional and, when present, must match the run (a budget for another setup is an error).
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "engine/perf/statistics.h"

namespace lantern::perf {

struct BudgetLimits {
  std::optional<double> frame;           // frame time (sum of the frame's GPU passes)
  std::map<std::string, double> passes;  // by pass name (module.stage)
};

struct Budget {
  std::string source;  // file name, for messages
  std::optional<std::string> level;
  std::optional<std::pair<unsigned, unsigned>> size;
  std::optional<std::string> integrator;
  std::optional<std::string> preset;
  std::string statistic = "median";  // median | p95 | p99 | max
  std::optional<BudgetLimits> relative;
  std::vector<std::pair<std::string, BudgetLimits>> absolute;  // (device substring, limits)
};

// What a bench run measured, as the budget check needs it.
struct BenchMeasurement {
  std::string level;
  std::pair<unsigned, unsigned> size{0, 0};
  std::string integrator;
  std::string preset;
  std::string device;
  double calibration_ms = 0.0;  // median GPU ms of the calibration workload in this run
  Summary frame;
  std::map<std::string, Summary> passes;
};

struct BudgetViolation {
  std::string what;  // "frame" or the pass name
  double measured = 0.0;
  double limit = 0.0;
  std::string unit;  // "ms" or "x calibration"
};

struct BudgetResult {
  std::vector<std::string> checked;  // one line per limit checked, for the report
  std::vector<BudgetViolation> violations;
  bool passed() const { return violations.empty(); }
};

// Throws lantern::InputError naming the file and the field for malformed budgets.
Budget load_budget(const std::filesystem::path& path);
Budget parse_budget(const std::string& json_text, const std::string& source);

// Checks `m` against `b`. Throws InputError when the budget is for another level, size,
// integrator or preset, names a pass the run did not have, or when no limit applies at all
// (no relative limits and no absolute entry for this device).
BudgetResult check_budget(const Budget& b, const BenchMeasurement& m);

}  // namespace lantern::perf
