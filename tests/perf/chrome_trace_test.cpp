#include "engine/perf/chrome_trace.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "tests/runtime/scratch_dir.h"

namespace lantern::perf {
namespace {

TEST(ChromeTrace, CompleteEventsOnNamedTracks) {
  ChromeTrace trace;
  const int cpu = trace.track("CPU systems");
  const int gpu = trace.track("GPU passes");
  EXPECT_EQ(trace.track("CPU systems"), cpu);
  trace.event(cpu, "world.extract", 10.0, 5.0);
  trace.event(gpu, "restir.initial", 20.0, 1500.0);
  const auto j = nlohmann::json::parse(trace.json());
  const auto& events = j.at("traceEvents");
  int complete = 0;
  int names = 0;
  for (const auto& e : events) {
    if (e.at("ph") == "X") {
      ++complete;
      EXPECT_TRUE(e.contains("ts") && e.contains("dur") && e.contains("tid"));
    }
    if (e.at("ph") == "M") ++names;
  }
  EXPECT_EQ(complete, 2);
  EXPECT_EQ(names, 2);
  EXPECT_EQ(events.back().at("name"), "restir.initial");
  EXPECT_DOUBLE_EQ(events.back().at("dur").get<double>(), 1500.0);
}

TEST(ChromeTrace, WritesAtomically) {
  const auto& dir = lantern::test::process_scratch_dir();
  ChromeTrace trace;
  trace.event(trace.track("t"), "e", 0.0, 1.0);
  trace.write(dir / "trace.json");
  EXPECT_TRUE(std::filesystem::exists(dir / "trace.json"));
  EXPECT_FALSE(std::filesystem::exists(dir / "trace.json.tmp"));
  EXPECT_ANY_THROW(trace.write(dir / "missing_dir" / "trace.json"));
}

}  // namespace
}  // namespace lantern::perf
