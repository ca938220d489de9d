// Culling of passes nobody needs, execution order, lifetimes and aliasing of transient memory.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "runtime/graph/alias_planner.h"
#include "tests/graph/graph_test_util.h"

namespace lantern::runtime::graph {
namespace {

using test::Empty;
using test::kNoExecute;
using test::position;

struct Out {
  BufferHandle v;
};

// A compute pass reading `in` (if valid) and writing a new transient of `bytes`.
const Out& chain(RenderGraph& g, const char* name, BufferHandle in, uint64_t bytes) {
  return g.add_pass<Out>(
      name, PassKind::Compute,
      [&, name](PassBuilder& b, Out& d) {
        if (in) b.read(in, Access::StorageRead);
        d.v = b.write(g.create_buffer(std::string(name) + ".out", {bytes}), Access::StorageWrite);
      },
      kNoExecute);
}

void consume(RenderGraph& g, const char* name, BufferHandle in, BufferHandle sink) {
  g.add_pass<Empty>(
      name, PassKind::Compute,
      [&](PassBuilder& b, Empty&) {
        b.read(in, Access::StorageRead);
        (void)b.write(sink, Access::StorageWrite);
      },
      kNoExecute);
}

TEST(GraphCulling, PassesWhoseOutputsNobodyReadsAreCulledTransitively) {
  RenderGraph g;
  const BufferHandle sink = g.import_buffer("sink", VK_NULL_HANDLE, {16});
  const Out& a = chain(g, "test.a", {}, 256);
  const Out& unused_1 = chain(g, "test.unused_1", a.v, 256);
  chain(g, "test.unused_2", unused_1.v, 256);
  consume(g, "test.b", a.v, sink);
  g.add_pass<Empty>(
      "test.debug", PassKind::Compute,
      [&](PassBuilder& b, Empty&) {
        b.read(a.v, Access::StorageRead);
        b.side_effect();
      },
      kNoExecute);
  g.bake();

  EXPECT_TRUE(position(g, "test.a"));
  EXPECT_TRUE(position(g, "test.b"));
  EXPECT_TRUE(position(g, "test.debug")) << "side-effect passes are never culled";
  EXPECT_FALSE(position(g, "test.unused_1")) << g.dump();
  EXPECT_FALSE(position(g, "test.unused_2")) << g.dump();
  EXPECT_EQ(g.compiled().culled.size(), 2u);
  EXPECT_NE(g.dump().find("culled: test.unused_1"), std::string::npos);
}

TEST(GraphCulling, AWriteThatIsOverwrittenUnreadIsCulled) {
  RenderGraph g;
  const BufferHandle sink = g.import_buffer("sink", VK_NULL_HANDLE, {16});
  const BufferHandle buf = g.create_buffer("buf", {64});
  const Out& first = g.add_pass<Out>(
      "test.first", PassKind::Compute,
      [&](PassBuilder& b, Out& d) { d.v = b.write(buf, Access::StorageWrite); }, kNoExecute);
  const Out& second = g.add_pass<Out>(
      "test.second", PassKind::Transfer,
      [&](PassBuilder& b, Out& d) { d.v = b.write(first.v, Access::TransferDst); }, kNoExecute);
  consume(g, "test.use", second.v, sink);
  g.bake();
  EXPECT_FALSE(position(g, "test.first")) << g.dump();
  EXPECT_TRUE(position(g, "test.second"));
}

TEST(GraphOrder, DeclarationOrderIsKeptWhenValid) {
  RenderGraph g;
  const BufferHandle sink = g.import_buffer("sink", VK_NULL_HANDLE, {16});
  const Out& x = chain(g, "test.x", {}, 64);
  const Out& y = chain(g, "test.y", {}, 64);  // independent of x
  const Out& z = chain(g, "test.z", y.v, 64);
  consume(g, "test.sink_x", x.v, sink);
  g.add_pass<Empty>(
      "test.sink_z", PassKind::Compute,
      [&](PassBuilder& b, Empty&) {
        b.read(z.v, Access::StorageRead);
        b.side_effect();
      },
      kNoExecute);
  g.bake();
  const char* expected[] = {"test.x", "test.y", "test.z", "test.sink_x", "test.sink_z"};
  for (size_t i = 0; i < 5; ++i) EXPECT_EQ(position(g, expected[i]), i) << g.dump();
}

TEST(GraphOrder, AStaleReadRunsBeforeTheOverwrite) {
  RenderGraph g;
  const BufferHandle buf = g.import_buffer("state", VK_NULL_HANDLE, {64});
  const Out& update = g.add_pass<Out>(
      "test.update", PassKind::Compute,
      [&](PassBuilder& b, Out& d) { d.v = b.write(buf, Access::StorageReadWrite); }, kNoExecute);
  // Declared later but reads the version before the update: must run first.
  g.add_pass<Empty>(
      "test.old_reader", PassKind::Compute,
      [&](PassBuilder& b, Empty&) {
        b.read(buf, Access::StorageRead);
        b.side_effect();
      },
      kNoExecute);
  (void)update;
  g.bake();
  EXPECT_EQ(position(g, "test.old_reader"), 0u) << g.dump();
  EXPECT_EQ(position(g, "test.update"), 1u) << g.dump();
}

TEST(GraphAliasing, TransientsWithDisjointLifetimesShareMemory) {
  RenderGraph g;
  const BufferHandle sink = g.import_buffer("sink", VK_NULL_HANDLE, {16});
  constexpr uint64_t kBytes = 1 << 20;
  const Out& a = chain(g, "test.a", {}, kBytes);   // lives in passes 0..1
  const Out& b = chain(g, "test.b", a.v, kBytes);  // 1..2
  const Out& c = chain(g, "test.c", b.v, kBytes);  // 2..3
  consume(g, "test.d", c.v, sink);
  g.bake();
  const CompiledGraph& compiled = g.compiled();

  EXPECT_EQ(compiled.lifetimes[a.v.index].first, 0u);
  EXPECT_EQ(compiled.lifetimes[a.v.index].last, 1u);
  EXPECT_EQ(compiled.lifetimes[c.v.index].first, 2u);
  EXPECT_EQ(compiled.memory_offset(a.v.index), compiled.memory_offset(c.v.index)) << g.dump();
  EXPECT_NE(compiled.memory_offset(a.v.index), compiled.memory_offset(b.v.index)) << g.dump();
  EXPECT_EQ(compiled.alias_plan.unaliased_size, 3 * kBytes);
  EXPECT_EQ(compiled.alias_plan.block_size, 2 * kBytes);
  EXPECT_EQ(compiled.alias_plan.saved(), kBytes);

  // c's first use waits for a's last use of the same bytes.
  const auto barrier = test::barrier_before(g, "test.c", c.v.index);
  ASSERT_TRUE(barrier) << g.dump();
  EXPECT_TRUE(barrier->aliasing);
  EXPECT_EQ(barrier->src.stages, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
  EXPECT_EQ(barrier->src.access, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  EXPECT_NE(g.dump().find("saved"), std::string::npos);
}

TEST(GraphAliasing, PlannerNeverOverlapsLiveResources) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<AliasRequest> requests(1 + rng() % 24);
    for (AliasRequest& r : requests) {
      r.size = 1 + rng() % 5000;
      r.alignment = uint64_t{1} << (rng() % 9);
      r.first_pass = rng() % 16;
      r.last_pass = r.first_pass + rng() % 6;
    }
    const AliasPlan plan = plan_aliasing(requests);
    ASSERT_EQ(plan.offsets.size(), requests.size());
    ASSERT_LE(plan.block_size, plan.unaliased_size);
    for (size_t i = 0; i < requests.size(); ++i) {
      EXPECT_EQ(plan.offsets[i] % requests[i].alignment, 0u);
      EXPECT_LE(plan.offsets[i] + requests[i].size, plan.block_size);
      for (size_t j = i + 1; j < requests.size(); ++j) {
        const bool live_together = requests[i].first_pass <= requests[j].last_pass &&
                                   requests[j].first_pass <= requests[i].last_pass;
        if (live_together) {
          ASSERT_FALSE(memory_overlaps(plan, requests, i, j)) << "trial " << trial;
        }
      }
    }
  }
}

}  // namespace
}  // namespace lantern::runtime::graph
