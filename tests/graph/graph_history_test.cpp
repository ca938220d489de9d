// History resources: last frame's version is absent on the first frame, present on the second,
// absent after a resize, a camera cut, or a frame that did not write it; slots ping-pong and
// their sync state carries across frames.
#include <gtest/gtest.h>

#include "tests/graph/graph_test_util.h"

namespace lantern::runtime::graph {
namespace {

using test::kNoExecute;

struct TemporalData {
  ImageHandle previous;  // invalid when there is no history
  ImageHandle current;
};

constexpr ImageDesc desc_of(uint32_t width) {
  return {{width, 90, 1}, VK_FORMAT_R16G16B16A16_SFLOAT};
}

// One frame of a temporal pass: reads last frame's image if any, writes this frame's.
TemporalData temporal_frame(RenderGraph& g, uint32_t width = 160, bool camera_cut = false) {
  g.begin_frame();
  if (camera_cut) g.invalidate_history();
  const ImageHandle current = g.create_history_image("taa.color", desc_of(width));
  const ImageHandle previous = g.history(current);
  const TemporalData& d = g.add_pass<TemporalData>(
      "taa.resolve", PassKind::Compute,
      [&](PassBuilder& b, TemporalData& data) {
        data.previous = previous;
        if (previous) b.read(previous, Access::StorageRead);  // the pass copes without history
        data.current = b.write(current, Access::StorageWrite);
      },
      kNoExecute);
  const TemporalData result = d;
  g.bake();
  g.end_frame();
  return result;
}

TEST(GraphHistory, AbsentOnFirstFramePresentOnSecond) {
  RenderGraph g;
  const TemporalData f1 = temporal_frame(g);
  EXPECT_FALSE(f1.previous.valid());
  EXPECT_TRUE(f1.current.valid());
  const TemporalData f2 = temporal_frame(g);
  EXPECT_TRUE(f2.previous.valid());
}

TEST(GraphHistory, SlotsPingPong) {
  RenderGraph g;
  temporal_frame(g);
  uint32_t last_write = ~0u;
  for (int frame = 0; frame < 4; ++frame) {
    temporal_frame(g);
    const GraphDecl& d = g.decl();
    uint32_t write = ~0u, read = ~0u;
    for (const ResourceDecl& r : d.resources) {
      if (r.origin == Origin::History) write = r.history_slot;
      if (r.origin == Origin::HistoryPrevious) read = r.history_slot;
    }
    EXPECT_NE(write, read);
    EXPECT_NE(write, last_write);
    last_write = write;
  }
}

TEST(GraphHistory, AbsentAfterResize) {
  RenderGraph g;
  temporal_frame(g, 160);
  temporal_frame(g, 160);
  EXPECT_FALSE(temporal_frame(g, 320).previous.valid());
  EXPECT_TRUE(temporal_frame(g, 320).previous.valid());
}

TEST(GraphHistory, AbsentAfterCameraCut) {
  RenderGraph g;
  temporal_frame(g);
  EXPECT_TRUE(temporal_frame(g).previous.valid());
  EXPECT_FALSE(temporal_frame(g, 160, /*camera_cut=*/true).previous.valid());
  EXPECT_TRUE(temporal_frame(g).previous.valid());
}

TEST(GraphHistory, AbsentWhenLastFrameDidNotWriteIt) {
  RenderGraph g;
  temporal_frame(g);
  g.begin_frame();  // a frame that declares nothing
  g.bake();
  g.end_frame();
  EXPECT_FALSE(temporal_frame(g).previous.valid());
}

TEST(GraphHistory, ReadingHistoryWaitsForLastFramesWrite) {
  RenderGraph g;
  temporal_frame(g);
  const TemporalData f2 = temporal_frame(g);
  // Frame 2 was baked: the read of slot written in frame 1 starts from frame 1's final state.
  ASSERT_TRUE(f2.previous.valid());
  const auto b = test::barrier_before(g, "taa.resolve", f2.previous.index);
  ASSERT_TRUE(b);
  EXPECT_EQ(b->src.stages, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
  EXPECT_EQ(b->src.access, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  EXPECT_EQ(b->src.layout, VK_IMAGE_LAYOUT_GENERAL);
  EXPECT_EQ(b->dst.access, VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
  // The written slot was last read in frame 2's predecessor... here frame 1 only wrote the
  // other slot, so this frame's write slot starts undefined (first use) or from a read.
  const auto w = test::barrier_before(g, "taa.resolve", f2.current.index);
  ASSERT_TRUE(w);
  EXPECT_EQ(w->dst.layout, VK_IMAGE_LAYOUT_GENERAL);
}

TEST(GraphHistory, HistoryWritesAreNeverCulled) {
  RenderGraph g;
  temporal_frame(g);
  EXPECT_TRUE(test::position(g, "taa.resolve"));
  EXPECT_TRUE(g.compiled().culled.empty());
}

TEST(HistoryTracker, DecidesSlotsAndValidity) {
  HistoryTracker t;
  const HistoryDesc desc = BufferDesc{1024};
  t.begin_frame();
  HistoryTracker::Slots s = t.declare("restir.reservoirs", desc);
  EXPECT_TRUE(s.recreated);
  EXPECT_FALSE(s.read_valid);
  t.mark_written("restir.reservoirs");
  t.begin_frame();
  s = t.declare("restir.reservoirs", desc);
  EXPECT_TRUE(s.read_valid);
  EXPECT_FALSE(s.recreated);
  EXPECT_EQ(s.read, 0u);
  EXPECT_EQ(s.write, 1u);
  t.mark_written("restir.reservoirs");
  t.begin_frame();
  s = t.declare("restir.reservoirs", desc);
  EXPECT_EQ(s.read, 1u);
  EXPECT_EQ(s.write, 0u);
  EXPECT_THROW((void)t.declare("restir.reservoirs", desc), RuntimeError);
  t.begin_frame();
  t.invalidate_all();
  s = t.declare("restir.reservoirs", desc);
  EXPECT_FALSE(s.read_valid);
  t.begin_frame();
  s = t.declare("restir.reservoirs", HistoryDesc{BufferDesc{2048}});
  EXPECT_TRUE(s.recreated);
  EXPECT_FALSE(s.read_valid);
}

}  // namespace
}  // namespace lantern::runtime::graph
