// ReservoirBuffers: for every chain shape, each pass reads what the previous one wrote, no pass
// reads and writes one buffer, the last resampling pass writes Final (next frame's history), only
// restir.temporal reads History and only when history is valid.
#include "lighting/restir/reservoir_buffers.h"

#include <gtest/gtest.h>

namespace lantern::lighting {
namespace {

TEST(ReservoirBuffers, ChainInvariantsForEveryShape) {
  for (bool temporal : {false, true}) {
    for (bool history : {false, true}) {
      for (std::uint32_t spatial = 0; spatial <= 4; ++spatial) {
        const auto steps = ReservoirBuffers::plan({temporal, spatial, history});
        SCOPED_TRACE(describe(steps));
        ASSERT_EQ(steps.size(), 2u + (temporal ? 1u : 0u) + spatial);
        EXPECT_EQ(steps.front().stage, ReservoirStage::Initial);
        EXPECT_EQ(steps.front().read, ReservoirBuffer::None);
        EXPECT_EQ(steps.back().stage, ReservoirStage::Shade);
        EXPECT_EQ(steps.back().read, ReservoirBuffer::Final);
        EXPECT_EQ(steps.back().write, ReservoirBuffer::None);
        // The pass before shade writes Final; nobody else does.
        for (std::size_t i = 0; i + 1 < steps.size(); ++i) {
          EXPECT_EQ(steps[i].write == ReservoirBuffer::Final, i + 2 == steps.size()) << i;
          EXPECT_NE(steps[i].write, ReservoirBuffer::None);
          EXPECT_NE(steps[i].write, ReservoirBuffer::History);
          EXPECT_NE(steps[i].read, steps[i].write) << "pass " << i << " reads and writes one buffer";
          EXPECT_EQ(steps[i + 1].read, steps[i].write) << "pass " << i + 1 << " input";
        }
        for (const ReservoirStep& s : steps) {
          const bool reads_history = s.history == ReservoirBuffer::History;
          EXPECT_EQ(reads_history, s.stage == ReservoirStage::Temporal && history);
          EXPECT_NE(s.read, ReservoirBuffer::History);
        }
        std::uint32_t expected_index = 0;
        for (const ReservoirStep& s : steps) {
          if (s.stage == ReservoirStage::Spatial) {
            EXPECT_EQ(s.spatial_index, expected_index++);
          }
        }
      }
    }
  }
}

TEST(ReservoirBuffers, DefaultChainPingPongs) {
  EXPECT_EQ(describe(ReservoirBuffers::plan({true, 3, true})),
            "restir.initial: - -> a; restir.temporal: a + history -> b; "
            "restir.spatial[0]: b -> a; restir.spatial[1]: a -> b; restir.spatial[2]: b -> final; "
            "restir.shade: final");
  EXPECT_EQ(describe(ReservoirBuffers::plan({false, 0, true})),
            "restir.initial: - -> final; restir.shade: final");
  EXPECT_EQ(describe(ReservoirBuffers::plan({true, 0, false})),
            "restir.initial: - -> a; restir.temporal: a -> final; restir.shade: final");
}

TEST(ReservoirBuffers, NoHistoryOnTheFirstFrameOrAfterReset) {
  ReservoirBuffers buffers;
  auto temporal_history = [](const std::vector<ReservoirStep>& steps) {
    for (const ReservoirStep& s : steps)
      if (s.stage == ReservoirStage::Temporal) return s.history;
    return ReservoirBuffer::None;
  };
  EXPECT_EQ(temporal_history(buffers.next_frame({true, 1, true})), ReservoirBuffer::None);
  EXPECT_EQ(temporal_history(buffers.next_frame({true, 1, true})), ReservoirBuffer::History);
  EXPECT_EQ(temporal_history(buffers.next_frame({true, 1, false})), ReservoirBuffer::None)
      << "camera cut";
  EXPECT_EQ(temporal_history(buffers.next_frame({true, 1, true})), ReservoirBuffer::History);
  buffers.reset();
  EXPECT_EQ(temporal_history(buffers.next_frame({true, 1, true})), ReservoirBuffer::None);
}

}  // namespace
}  // namespace lantern::lighting
