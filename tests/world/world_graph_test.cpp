// The world's systems land in the right phases with the orderings their declarations imply.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "world_levels.h"

namespace lantern {
namespace {

// Parses SystemGraph::describe(): phase name → system names, sorted (order is checked by edges).
std::map<std::string, std::vector<std::string>> systems_by_phase(const std::string& dump) {
  std::map<std::string, std::vector<std::string>> out;
  std::istringstream in(dump);
  std::string line, phase;
  while (std::getline(in, line)) {
    if (line.rfind("phase ", 0) == 0) {
      phase = line.substr(6);
    } else if (line.rfind("  ", 0) == 0 && line.rfind("    ", 0) != 0) {
      out[phase].push_back(line.substr(2, line.find(' ', 2) - 2));
    }
  }
  for (auto& [name, systems] : out) std::sort(systems.begin(), systems.end());
  return out;
}

TEST(WorldGraph, DumpListsSystemsInTheirPhases) {
  World world(test::animated_level(), {.threads = 2});
  const auto phases = systems_by_phase(world.scheduler().describe());
  using V = std::vector<std::string>;
  EXPECT_EQ(phases.count("Input"), 0u);
  EXPECT_EQ(phases.at("Simulate"), (V{"world.camera_path", "world.flicker", "world.follow_path",
                                      "world.orbit", "world.rotate"}));
  EXPECT_EQ(phases.at("Transform"), (V{"world.camera_history", "world.transforms"}));
  EXPECT_EQ(phases.at("Extract"), (V{"world.extract"}));
}

TEST(WorldGraph, OrderingFollowsDeclarations) {
  World world(test::animated_level(), {.threads = 2});
  const SystemGraph& g = world.scheduler().graph();
  // The three Transform writers are chained in declaration order.
  EXPECT_TRUE(g.has_edge("world.rotate", "world.orbit"));
  EXPECT_TRUE(g.has_edge("world.orbit", "world.follow_path"));
  // Flicker and the camera touch other data: free to run beside the movers.
  for (const char* mover : {"world.rotate", "world.orbit", "world.follow_path"}) {
    EXPECT_FALSE(g.ordered(mover, "world.flicker"));
    EXPECT_FALSE(g.ordered("world.flicker", mover));
    EXPECT_FALSE(g.ordered(mover, "world.camera_path"));
  }
  EXPECT_FALSE(g.ordered("world.transforms", "world.camera_history"));
  EXPECT_FALSE(g.ordered("world.camera_history", "world.transforms"));
  // Phases order the rest.
  EXPECT_TRUE(g.ordered("world.follow_path", "world.transforms"));
  EXPECT_TRUE(g.ordered("world.transforms", "world.extract"));
  EXPECT_TRUE(g.ordered("world.camera_history", "world.extract"));
}

TEST(WorldGraph, DumpNamesDeclaredAccess) {
  World world(test::animated_level(), {.threads = 1});
  const std::string dump = world.scheduler().describe();
  const std::size_t at = dump.find("  world.transforms");
  ASSERT_NE(at, std::string::npos);
  const std::string block = dump.substr(at, dump.find("  world.camera_history") - at);
  EXPECT_NE(block.find("WorldMatrix"), std::string::npos) << block;
  EXPECT_NE(block.find("PreviousTransform"), std::string::npos) << block;
}

}  // namespace
}  // namespace lantern
