// The scheduler's graph follows from the declarations alone: these tests check its shape (edges,
// ordering, phases) for several declared sets, and that malformed declarations are rejected.
#include <gtest/gtest.h>

#include "engine/sched/scheduler.h"

namespace lantern {
namespace {

struct P {};
struct Q {};
struct R {};
struct Settings {};

const SystemFn kNoop = [](Registry&, const FrameTime&) {};

TEST(SchedulerGraph, WriterThenReadersThenWriter) {
  Scheduler s;
  s.add("a", Phase::Simulate).writes<P>().run(kNoop);
  s.add("b", Phase::Simulate).reads<P>().run(kNoop);
  s.add("c", Phase::Simulate).reads<P>().run(kNoop);
  s.add("d", Phase::Simulate).writes<P>().run(kNoop);
  const SystemGraph& g = s.graph();
  EXPECT_TRUE(g.has_edge("a", "b"));
  EXPECT_TRUE(g.has_edge("a", "c"));
  EXPECT_TRUE(g.has_edge("b", "d"));
  EXPECT_TRUE(g.has_edge("c", "d"));
  EXPECT_FALSE(g.has_edge("a", "d"));  // implied by a→b→d
  EXPECT_TRUE(g.ordered("a", "d"));
  EXPECT_FALSE(g.ordered("b", "c"));  // readers share
  EXPECT_FALSE(g.ordered("c", "b"));
  EXPECT_EQ(g.nodes()[3].after, (std::vector<std::uint32_t>{1, 2}));
}

TEST(SchedulerGraph, IndependentSystemsHaveNoEdges) {
  Scheduler s;
  s.add("p", Phase::Simulate).writes<P>().run(kNoop);
  s.add("q", Phase::Simulate).writes<Q>().reads<Settings>().run(kNoop);
  s.add("r", Phase::Simulate).writes<R>().reads<Settings>().run(kNoop);
  for (const auto& n : s.graph().nodes()) {
    EXPECT_TRUE(n.after.empty()) << n.name;
    EXPECT_TRUE(n.before.empty()) << n.name;
  }
}

TEST(SchedulerGraph, WriteWriteConflictsFollowDeclarationOrder) {
  Scheduler s;
  s.add("second", Phase::Simulate).writes<P>().run(kNoop);
  s.add("first", Phase::Simulate).writes<P>().run(kNoop);
  EXPECT_TRUE(s.graph().has_edge("second", "first"));
  EXPECT_FALSE(s.graph().has_edge("first", "second"));
}

TEST(SchedulerGraph, TransitiveEdgesAreReduced) {
  Scheduler s;
  s.add("a", Phase::Transform).writes<P>().run(kNoop);
  s.add("b", Phase::Transform).reads<P>().writes<Q>().run(kNoop);
  s.add("c", Phase::Transform).reads<P, Q>().run(kNoop);
  const SystemGraph& g = s.graph();
  EXPECT_TRUE(g.has_edge("a", "b"));
  EXPECT_TRUE(g.has_edge("b", "c"));
  EXPECT_FALSE(g.has_edge("a", "c"));
  EXPECT_TRUE(g.ordered("a", "c"));
}

TEST(SchedulerGraph, ExclusiveSystemSplitsItsPhase) {
  Scheduler s;
  s.add("before", Phase::Simulate).writes<P>().run(kNoop);
  s.add("spawn", Phase::Simulate).exclusive().run(kNoop);
  s.add("after", Phase::Simulate).writes<Q>().run(kNoop);
  const SystemGraph& g = s.graph();
  EXPECT_TRUE(g.has_edge("before", "spawn"));
  EXPECT_TRUE(g.has_edge("spawn", "after"));
  EXPECT_FALSE(g.has_edge("before", "after"));
}

TEST(SchedulerGraph, PhasesOrderSystemsWithoutEdges) {
  Scheduler s;
  s.add("render", Phase::Render).reads<P>().run(kNoop);
  s.add("sim", Phase::Simulate).writes<P>().run(kNoop);
  s.add("input", Phase::Input).writes<P>().run(kNoop);
  const SystemGraph& g = s.graph();
  EXPECT_FALSE(g.has_edge("sim", "render"));  // phases are barriers, not edges
  EXPECT_TRUE(g.ordered("input", "sim"));
  EXPECT_TRUE(g.ordered("sim", "render"));
  EXPECT_FALSE(g.ordered("render", "input"));
  EXPECT_EQ(g.phase(Phase::Simulate), (std::vector<std::uint32_t>{1}));
  EXPECT_TRUE(g.phase(Phase::Extract).empty());
}

TEST(SchedulerGraph, DescribeListsPhasesAccessAndPredecessors) {
  Scheduler s;
  s.add("anim.rotate", Phase::Simulate).writes<P>().run(kNoop);
  s.add("xform.update", Phase::Simulate).reads<P>().writes<Q>().run(kNoop);
  const std::string text = s.describe();
  EXPECT_NE(text.find("phase Simulate"), std::string::npos) << text;
  EXPECT_NE(text.find("xform.update"), std::string::npos) << text;
  EXPECT_NE(text.find("after: anim.rotate"), std::string::npos) << text;
  EXPECT_EQ(text.find("phase Render"), std::string::npos) << text;
}

void expect_rejected(Scheduler& s, const std::string& fragment) {
  try {
    s.build();
    FAIL() << "expected rejection mentioning: " << fragment;
  } catch (const RuntimeError& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

TEST(SchedulerGraph, RejectsMalformedDeclarations) {
  {
    Scheduler s;
    s.add("", Phase::Simulate).writes<P>().run(kNoop);
    expect_rejected(s, "no name");
  }
  {
    Scheduler s;
    s.add("twice", Phase::Simulate).writes<P>().run(kNoop);
    s.add("twice", Phase::Render).writes<Q>().run(kNoop);
    expect_rejected(s, "'twice'");
  }
  {
    Scheduler s;
    s.add("nofn", Phase::Simulate).writes<P>();
    expect_rejected(s, "no function");
  }
  {
    Scheduler s;
    s.add("silent", Phase::Simulate).run(kNoop);
    expect_rejected(s, "declares no reads or writes");
  }
  {
    Scheduler s;
    s.add("both", Phase::Simulate).reads<P>().writes<P>().run(kNoop);
    expect_rejected(s, "both read and written");
  }
  {
    Scheduler s;
    s.add("dup", Phase::Simulate).reads<P, Q, P>().run(kNoop);
    expect_rejected(s, "twice");
  }
}

}  // namespace
}  // namespace lantern
