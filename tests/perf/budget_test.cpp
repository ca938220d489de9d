#include "engine/perf/budget.h"

#include <gtest/gtest.h>

#include "engine/core/error.h"

namespace lantern::perf {
namespace {

Summary ms(double median) {
  Summary s;
  s.median = median;
  s.p95 = median * 1.1;
  s.p99 = median * 1.2;
  s.max = median * 1.5;
  s.count = 10;
  return s;
}

BenchMeasurement run() {
  BenchMeasurement m;
  m.level = "cornell_lights";
  m.size = {320, 180};
  m.integrator = "restir";
  m.preset = "balanced";
  m.device = "llvmpipe (LLVM 15.0.6, 256 bits)";
  m.calibration_ms = 2.0;
  m.frame = ms(20.0);
  m.passes["gbuffer"] = ms(4.0);
  m.passes["restir.shade"] = ms(6.0);
  return m;
}

TEST(Budget, RelativeLimitsScaleWithCalibration) {
  const Budget b = parse_budget(
      R"({"relative": {"frame": 11.0, "passes": {"gbuffer": 1.5, "restir.shade": 3.5}}})", "b");
  const BudgetResult r = check_budget(b, run());  // frame 10x, gbuffer 2x, shade 3x
  ASSERT_EQ(r.violations.size(), 1u);
  EXPECT_EQ(r.violations[0].what, "gbuffer");
  EXPECT_DOUBLE_EQ(r.violations[0].measured, 2.0);
  EXPECT_EQ(r.checked.size(), 3u);

  BenchMeasurement slower = run();  // everything 2x slower, calibration too: still the same
  slower.calibration_ms *= 2.0;
  slower.frame = ms(40.0);
  slower.passes["gbuffer"] = ms(8.0);
  slower.passes["restir.shade"] = ms(12.0);
  EXPECT_EQ(check_budget(b, slower).violations.size(), 1u);
}

TEST(Budget, AbsoluteLimitsApplyOnlyToTheirDevice) {
  const Budget b = parse_budget(
      R"({"absolute": [{"device": "llvmpipe", "frame": 19.0},
                       {"device": "RTX", "frame": 1.0}], "statistic": "median"})",
      "b");
  const BudgetResult r = check_budget(b, run());
  ASSERT_EQ(r.violations.size(), 1u);
  EXPECT_EQ(r.violations[0].what, "frame");
  EXPECT_EQ(r.violations[0].unit, "ms");

  BenchMeasurement other = run();
  other.device = "Some GPU";
  EXPECT_THROW(check_budget(b, other), InputError);  // nothing applies: an error, not a pass
}

TEST(Budget, StatisticSelectsTheFigure) {
  const Budget b = parse_budget(R"({"statistic": "max", "absolute": [
      {"device": "llvmpipe", "frame": 25.0}]})", "b");
  EXPECT_FALSE(check_budget(b, run()).passed());  // max = 30 ms
}

TEST(Budget, MismatchedSetupAndUnknownPassAreErrors) {
  EXPECT_THROW(check_budget(parse_budget(R"({"size": [640, 360], "relative": {"frame": 99}})", "b"),
                            run()),
               InputError);
  EXPECT_THROW(check_budget(parse_budget(R"({"level": "night_market", "relative": {"frame": 99}})",
                                         "b"),
                            run()),
               InputError);
  EXPECT_THROW(
      check_budget(parse_budget(R"({"relative": {"passes": {"restir.typo": 1}}})", "b"), run()),
      InputError);
}

TEST(Budget, MalformedFilesNameTheProblem) {
  for (const char* text :
       {"{", "[]", R"({"relative": {"frame": -1}})", R"({"relative": {"frame": "fast"}})",
        R"({"bogus": 1})", R"({"statistic": "mean"})", R"({"absolute": [{"frame": 1}]})",
        R"({"size": [0.5, 2]})"}) {
    EXPECT_THROW(parse_budget(text, "budget.json"), InputError) << text;
  }
  try {
    parse_budget(R"({"relative": {"frame": -1}})", "budget.json");
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("relative.frame"), std::string::npos) << e.what();
  }
  EXPECT_THROW(load_budget("/no/such/budget.json"), InputError);
}

}  // namespace
}  // namespace lantern::perf
