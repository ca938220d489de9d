// Barrier derivation of the render-graph compiler: read after write, write after read, write
// after write, image layout transitions, final transitions of imported resources.
#include <gtest/gtest.h>

#include "runtime/graph/barrier_recorder.h"
#include "tests/graph/graph_test_util.h"

namespace lantern::runtime::graph {
namespace {

using test::barrier_before;
using test::Empty;
using test::kNoExecute;

constexpr ImageDesc kImage{{64, 32, 1}, VK_FORMAT_R32G32B32A32_SFLOAT};

// Keeps a pass alive by making it write an imported buffer.
BufferHandle sink(RenderGraph& g) {
  return g.import_buffer("sink", VK_NULL_HANDLE, {64});
}

TEST(GraphBarriers, ReadAfterWriteMakesComputeWritesVisibleToReaders) {
  RenderGraph g;
  const BufferHandle out = sink(g);
  const BufferHandle data = g.create_buffer("data", {1024});
  struct W {
    BufferHandle v;
  };
  const W& w = g.add_pass<W>(
      "test.produce", PassKind::Compute,
      [&](PassBuilder& b, W& d) { d.v = b.write(data, Access::StorageWrite); }, kNoExecute);
  g.add_pass<Empty>(
      "test.consume", PassKind::Compute,
      [&](PassBuilder& b, Empty&) {
        b.read(w.v, Access::StorageRead);
        (void)b.write(out, Access::StorageWrite);
      },
      kNoExecute);
  g.bake();

  EXPECT_FALSE(barrier_before(g, "test.produce", data.index)) << g.dump();
  const auto b = barrier_before(g, "test.consume", data.index);
  ASSERT_TRUE(b) << g.dump();
  EXPECT_EQ(b->src.stages, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
  EXPECT_EQ(b->src.access, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  EXPECT_EQ(b->dst.stages, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
  EXPECT_EQ(b->dst.access, VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
  EXPECT_FALSE(b->aliasing);
}

// scene.tlas_build's shape: a TLAS build (reading host-written instance records) followed by a
// compute pass that traces it: the build's write reaches the shader's acceleration-structure read.
TEST(GraphBarriers, AccelerationStructureBuildIsVisibleToRayQueries) {
  RenderGraph g;
  const BufferHandle out = sink(g);
  const BufferHandle records =
      g.import_buffer("tlas_instances", VK_NULL_HANDLE, {64},
                      {.read_only = true,
                       .initial = {VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_WRITE_BIT,
                                   VK_IMAGE_LAYOUT_UNDEFINED}});
  const BufferHandle tlas = g.import_buffer("tlas", VK_NULL_HANDLE, {4096});
  struct W {
    BufferHandle tlas;
  };
  const W& w = g.add_pass<W>(
      "test.tlas_build", PassKind::Compute,
      [&](PassBuilder& b, W& d) {
        b.read(records, Access::AccelerationStructureBuildInput);
        d.tlas = b.write(tlas, Access::AccelerationStructureBuild);
      },
      kNoExecute);
  g.add_pass<Empty>(
      "test.trace", PassKind::Compute,
      [&](PassBuilder& b, Empty&) {
        b.read(w.tlas, Access::AccelerationStructureRead);
        (void)b.write(out, Access::StorageWrite);
      },
      kNoExecute);
  g.bake();

  const auto input = barrier_before(g, "test.tlas_build", records.index);
  ASSERT_TRUE(input) << g.dump();
  EXPECT_EQ(input->src.access, VK_ACCESS_2_HOST_WRITE_BIT);
  EXPECT_EQ(input->dst.stages, VK_PIPELINE_STAGE_2_ACCELERATION_STRUCTURE_BUILD_BIT_KHR);
  EXPECT_EQ(input->dst.access, VK_ACCESS_2_SHADER_READ_BIT);
  const auto b = barrier_before(g, "test.trace", tlas.index);
  ASSERT_TRUE(b) << g.dump();
  EXPECT_EQ(b->src.stages, VK_PIPELINE_STAGE_2_ACCELERATION_STRUCTURE_BUILD_BIT_KHR);
  EXPECT_EQ(b->src.access, VK_ACCESS_2_ACCELERATION_STRUCTURE_WRITE_BIT_KHR);
  EXPECT_EQ(b->dst.stages, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
  EXPECT_EQ(b->dst.access, VK_ACCESS_2_ACCELERATION_STRUCTURE_READ_BIT_KHR);
}

TEST(GraphBarriers, WriteAfterReadNeedsOnlyAnExecutionDependency) {
  RenderGraph g;
  // Imported with nothing pending: the only hazard is the graphics read before the copy.
  const BufferHandle buf = g.import_buffer("lights", VK_NULL_HANDLE, {256});
  g.add_pass<Empty>(
      "test.draw", PassKind::Graphics,
      [&](PassBuilder& b, Empty&) {
        b.read(buf, Access::StorageRead);
        b.side_effect();
      },
      kNoExecute);
  g.add_pass<Empty>(
      "test.upload", PassKind::Transfer,
      [&](PassBuilder& b, Empty&) { (void)b.write(buf, Access::TransferDst); }, kNoExecute);
  g.bake();

  EXPECT_FALSE(barrier_before(g, "test.draw", buf.index)) << g.dump();
  const auto b = barrier_before(g, "test.upload", buf.index);
  ASSERT_TRUE(b) << g.dump();
  EXPECT_EQ(b->src.stages,
            VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT);
  EXPECT_EQ(b->src.access, VK_ACCESS_2_NONE);
  EXPECT_EQ(b->dst.access, VK_ACCESS_2_TRANSFER_WRITE_BIT);
  EXPECT_NE(b->dst.stages & VK_PIPELINE_STAGE_2_COPY_BIT, 0u);
}

TEST(GraphBarriers, WriteAfterWriteMakesTheFirstWriteAvailable) {
  RenderGraph g;
  const BufferHandle out = sink(g);
  const BufferHandle acc = g.create_buffer("accum", {4096});
  struct H {
    BufferHandle v;
  };
  const H& first = g.add_pass<H>(
      "test.clear", PassKind::Transfer,
      [&](PassBuilder& b, H& d) { d.v = b.write(acc, Access::TransferDst); }, kNoExecute);
  const H& second = g.add_pass<H>(
      "test.accumulate", PassKind::Compute,
      [&](PassBuilder& b, H& d) { d.v = b.write(first.v, Access::StorageReadWrite); }, kNoExecute);
  g.add_pass<Empty>(
      "test.resolve", PassKind::Compute,
      [&](PassBuilder& b, Empty&) {
        b.read(second.v, Access::StorageRead);
        (void)b.write(out, Access::StorageWrite);
      },
      kNoExecute);
  g.bake();

  const auto b = barrier_before(g, "test.accumulate", acc.index);
  ASSERT_TRUE(b) << g.dump();
  EXPECT_NE(b->src.stages & VK_PIPELINE_STAGE_2_COPY_BIT, 0u);
  EXPECT_EQ(b->src.access, VK_ACCESS_2_TRANSFER_WRITE_BIT);
  EXPECT_EQ(b->dst.access,
            VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  const auto r = barrier_before(g, "test.resolve", acc.index);
  ASSERT_TRUE(r) << g.dump();
  EXPECT_EQ(r->src.access, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
}

TEST(GraphBarriers, ReadersInAnAlreadyVisibleScopeShareOneBarrier) {
  RenderGraph g;
  const BufferHandle out = sink(g);
  struct H {
    BufferHandle v;
  };
  const H& w = g.add_pass<H>(
      "test.produce", PassKind::Compute,
      [&](PassBuilder& b, H& d) {
        d.v = b.write(g.create_buffer("data", {64}), Access::StorageWrite);
      },
      kNoExecute);
  for (const char* name : {"test.read_a", "test.read_b"})
    g.add_pass<Empty>(
        name, PassKind::Compute,
        [&](PassBuilder& b, Empty&) {
          b.read(w.v, Access::StorageRead);
          b.side_effect();
        },
        kNoExecute);
  (void)out;
  g.bake();
  EXPECT_TRUE(barrier_before(g, "test.read_a", w.v.index)) << g.dump();
  EXPECT_FALSE(barrier_before(g, "test.read_b", w.v.index)) << g.dump();
}

TEST(GraphBarriers, ImageLayoutsFollowEachUse) {
  RenderGraph g;
  ImportInfo present;
  present.final =
      AccessState{VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR};
  const ImageHandle target =
      g.import_image("swapchain", VK_NULL_HANDLE, VK_NULL_HANDLE, kImage, present);
  struct I {
    ImageHandle v;
  };
  const I& lit = g.add_pass<I>(
      "test.light", PassKind::Compute,
      [&](PassBuilder& b, I& d) {
        d.v = b.write(g.create_image("radiance", kImage), Access::StorageWrite);
      },
      kNoExecute);
  g.add_pass<Empty>(
      "test.tonemap", PassKind::Graphics,
      [&](PassBuilder& b, Empty&) {
        b.read(lit.v, Access::Sampled);
        (void)b.write(target, Access::ColorAttachment);
      },
      kNoExecute);
  g.bake();

  const auto first = barrier_before(g, "test.light", lit.v.index);
  ASSERT_TRUE(first) << g.dump();
  EXPECT_EQ(first->src.layout, VK_IMAGE_LAYOUT_UNDEFINED);
  EXPECT_EQ(first->dst.layout, VK_IMAGE_LAYOUT_GENERAL);
  EXPECT_EQ(first->src.stages, VK_PIPELINE_STAGE_2_NONE);

  const auto sampled = barrier_before(g, "test.tonemap", lit.v.index);
  ASSERT_TRUE(sampled) << g.dump();
  EXPECT_EQ(sampled->src.layout, VK_IMAGE_LAYOUT_GENERAL);
  EXPECT_EQ(sampled->dst.layout, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
  EXPECT_EQ(sampled->src.access, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  EXPECT_EQ(sampled->dst.access, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);

  const auto attach = barrier_before(g, "test.tonemap", target.index);
  ASSERT_TRUE(attach) << g.dump();
  EXPECT_EQ(attach->dst.layout, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);

  const CompiledGraph& c = g.compiled();
  ASSERT_EQ(c.after.barriers.size(), 1u) << g.dump();
  EXPECT_EQ(c.after.barriers[0].resource, target.index);
  EXPECT_EQ(c.after.barriers[0].src.layout, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
  EXPECT_EQ(c.after.barriers[0].src.access & VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT,
            VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);
  EXPECT_EQ(c.after.barriers[0].dst.layout, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR);
}

// Raster write, compute read (GENERAL), transfer read (TRANSFER_SRC_OPTIMAL): the second
// transition waits for the compute reads with no access of its own; the first barrier already
// made the colour write available. (It used to carry COLOR_ATTACHMENT_WRITE with the COMPUTE
// stage: VUID-VkImageMemoryBarrier2-srcAccessMask-03911, seen reading back gbuffer.ids.)
TEST(GraphBarriers, SecondTransitionAfterReadsCarriesNoEarlierWriteAccess) {
  RenderGraph g;
  const BufferHandle out = sink(g);
  struct I {
    ImageHandle v;
  };
  const I& drawn = g.add_pass<I>(
      "test.draw", PassKind::Graphics,
      [&](PassBuilder& b, I& d) {
        d.v = b.write(g.create_image("ids", kImage), Access::ColorAttachment);
      },
      kNoExecute);
  g.add_pass<Empty>(
      "test.shade", PassKind::Compute,
      [&](PassBuilder& b, Empty&) {
        b.read(drawn.v, Access::StorageRead);
        (void)b.write(out, Access::StorageWrite);
      },
      kNoExecute);
  g.add_pass<Empty>(
      "test.copy", PassKind::Transfer,
      [&](PassBuilder& b, Empty&) {
        b.read(drawn.v, Access::TransferSrc);
        b.side_effect();
      },
      kNoExecute);
  g.bake();

  const auto shade = barrier_before(g, "test.shade", drawn.v.index);
  ASSERT_TRUE(shade) << g.dump();
  EXPECT_EQ(shade->src.access, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);
  EXPECT_EQ(shade->dst.layout, VK_IMAGE_LAYOUT_GENERAL);
  const auto copy = barrier_before(g, "test.copy", drawn.v.index);
  ASSERT_TRUE(copy) << g.dump();
  EXPECT_EQ(copy->src.layout, VK_IMAGE_LAYOUT_GENERAL);
  EXPECT_EQ(copy->dst.layout, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
  EXPECT_NE(copy->src.stages & VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, 0u);
  EXPECT_EQ(copy->src.access, VK_ACCESS_2_NONE);
}

TEST(GraphBarriers, ReadbackBufferEndsWithAHostReadBarrier) {
  RenderGraph g;
  ImportInfo host;
  host.final = AccessState{VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT,
                           VK_IMAGE_LAYOUT_UNDEFINED};
  const BufferHandle readback = g.import_buffer("readback", VK_NULL_HANDLE, {16}, host);
  g.add_pass<Empty>(
      "test.reduce", PassKind::Compute,
      [&](PassBuilder& b, Empty&) { (void)b.write(readback, Access::StorageWrite); }, kNoExecute);
  g.bake();
  ASSERT_EQ(g.compiled().after.barriers.size(), 1u) << g.dump();
  const ResourceBarrier& b = g.compiled().after.barriers[0];
  EXPECT_EQ(b.src.access, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  EXPECT_EQ(b.dst.stages, VK_PIPELINE_STAGE_2_HOST_BIT);
  EXPECT_EQ(b.dst.access, VK_ACCESS_2_HOST_READ_BIT);
}

TEST(GraphBarriers, DumpListsPassesBarriersAndResources) {
  RenderGraph g;
  const BufferHandle out = sink(g);
  struct H {
    BufferHandle v;
  };
  const H& w = g.add_pass<H>(
      "test.produce", PassKind::Compute,
      [&](PassBuilder& b, H& d) {
        d.v = b.write(g.create_buffer("data", {64}), Access::StorageWrite);
      },
      kNoExecute);
  g.add_pass<Empty>(
      "test.consume", PassKind::Compute,
      [&](PassBuilder& b, Empty&) {
        b.read(w.v, Access::StorageRead);
        (void)b.write(out, Access::StorageWrite);
      },
      kNoExecute);
  g.bake();
  const std::string text = g.dump();
  for (const char* needle :
       {"test.produce", "test.consume", "barrier data",
        "COMPUTE_SHADER/SHADER_STORAGE_WRITE -> COMPUTE_SHADER/SHADER_STORAGE_READ",
        "sink buffer 64 B (imported)", "transient memory"})
    EXPECT_NE(text.find(needle), std::string::npos) << needle << "\n" << text;
}

}  // namespace
}  // namespace lantern::runtime::graph

namespace lantern::runtime::graph {
namespace {

TEST(GraphBarriers, Vulkan10MappingKeepsScopes) {
  EXPECT_EQ(to_stage1(VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, true),
            VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT);
  EXPECT_EQ(to_stage1(VK_PIPELINE_STAGE_2_COPY_BIT | VK_PIPELINE_STAGE_2_CLEAR_BIT, true),
            VK_PIPELINE_STAGE_TRANSFER_BIT);
  EXPECT_EQ(to_stage1(VK_PIPELINE_STAGE_2_NONE, true), VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT);
  EXPECT_EQ(to_stage1(VK_PIPELINE_STAGE_2_NONE, false), VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT);
  EXPECT_EQ(to_access1(VK_ACCESS_2_SHADER_STORAGE_READ_BIT), VK_ACCESS_SHADER_READ_BIT);
  EXPECT_EQ(to_access1(VK_ACCESS_2_SHADER_SAMPLED_READ_BIT), VK_ACCESS_SHADER_READ_BIT);
  EXPECT_EQ(to_access1(VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT), VK_ACCESS_SHADER_WRITE_BIT);
  EXPECT_EQ(to_access1(VK_ACCESS_2_HOST_READ_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT),
            VK_ACCESS_HOST_READ_BIT | VK_ACCESS_TRANSFER_WRITE_BIT);
}

}  // namespace
}  // namespace lantern::runtime::graph
