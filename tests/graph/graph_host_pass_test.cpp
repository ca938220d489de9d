// A host pass (PassKind::Host) between device passes, run on lavapipe with synchronization
// validation: a transfer pass fills a mapped buffer, the host pass sees every value the device
// wrote and overwrites them, a transfer pass copies what the host wrote to a second buffer. Over
// frames, the host always sees this frame's fill (not last frame's), the copy always sees the
// host's writes, and the timer reports the host pass among the device passes, in order. A host
// pass that needs no barrier runs at once instead (before the device passes declared ahead of
// it are submitted; the timer then reports it first), beside one that waits.
#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "runtime/core/device.h"
#include "runtime/gpu/buffer.h"
#include "runtime/gpu/gpu_timer.h"
#include "runtime/graph/graph_executor.h"

namespace lantern::runtime::graph {
namespace {

constexpr std::uint32_t kCount = 4096;

struct HostPassFixture {
  Device device{DeviceOptions{.validation = true, .sync_validation = true}};
  Buffer shared{device,
                {.size = kCount * sizeof(std::uint32_t),
                 .usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                 .memory = MemoryUsage::Readback,
                 .name = "test.shared"}};
  Buffer result{device,
                {.size = kCount * sizeof(std::uint32_t),
                 .usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                 .memory = MemoryUsage::Readback,
                 .name = "test.result"}};
  GraphExecutor executor{device};
  GpuTimer timer{device, 16};
  RenderGraph graph;

  // One frame: fill `value`, host checks and writes value * 1000 + i, copy. Returns what the host
  // saw wrong (0: every element held `value`).
  std::uint32_t frame(std::uint32_t value) {
    constexpr AccessState kAnyPriorUse{
        VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT | VK_PIPELINE_STAGE_2_HOST_BIT,
        VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT | VK_ACCESS_2_HOST_READ_BIT |
            VK_ACCESS_2_HOST_WRITE_BIT,
        VK_IMAGE_LAYOUT_UNDEFINED};
    graph.begin_frame();
    BufferHandle a = graph.import_buffer("test.shared", shared.handle(), {shared.size()},
                                         {.initial = kAnyPriorUse});
    const BufferHandle b = graph.import_buffer("test.result", result.handle(), {result.size()},
                                               {.initial = kAnyPriorUse});
    struct One {
      BufferHandle buffer;
    };
    a = graph
            .add_pass<One>(
                "test.fill", PassKind::Transfer,
                [&](PassBuilder& p, One& d) { d.buffer = p.write(a, Access::TransferDst); },
                [value](PassContext& ctx, const One& d) {
                  vkCmdFillBuffer(ctx.cmd(), ctx.buffer(d.buffer), 0, VK_WHOLE_SIZE, value);
                })
            .buffer;
    std::uint32_t wrong = 0;
    a = graph
            .add_pass<One>(
                "test.host", PassKind::Host,
                [&](PassBuilder& p, One& d) { d.buffer = p.write(a, Access::HostReadWrite); },
                [&, value](PassContext& ctx, const One&) {
                  EXPECT_EQ(ctx.cmd(), VK_NULL_HANDLE) << "a host pass records nothing";
                  auto* v = reinterpret_cast<std::uint32_t*>(shared.mapped());
                  for (std::uint32_t i = 0; i < kCount; ++i) {
                    wrong += v[i] != value ? 1u : 0u;
                    v[i] = value * 1000u + i;
                  }
                })
            .buffer;
    struct Copy {
      BufferHandle from, to;
    };
    graph.add_pass<Copy>(
        "test.copy", PassKind::Transfer,
        [&](PassBuilder& p, Copy& d) {
          p.read(a, Access::TransferSrc);
          d.from = a;
          d.to = p.write(b, Access::TransferDst);
          p.side_effect();
        },
        [](PassContext& ctx, const Copy& d) {
          const VkBufferCopy region{0, 0, kCount * sizeof(std::uint32_t)};
          vkCmdCopyBuffer(ctx.cmd(), ctx.buffer(d.from), ctx.buffer(d.to), 1, &region);
        });
    graph.bake(executor.compile_options());
    timer.reset_on_host();  // the fill runs in a submission before the caller's
    device.submit_and_wait([&](VkCommandBuffer cmd) { executor.record(graph, cmd, &timer); });
    graph.end_frame();
    return wrong;
  }
};

TEST(GraphHostPass, RunsBetweenSubmissionsAndSeesTheDevicesWrites) {
  HostPassFixture f;
  ASSERT_TRUE(f.device.sync_validation_enabled());
  for (const std::uint32_t value : {7u, 11u, 13u}) {
    EXPECT_EQ(f.frame(value), 0u) << "the host read stale values in frame " << value;
    std::vector<std::uint32_t> copied(kCount);
    std::memcpy(copied.data(), f.result.mapped(), kCount * sizeof(std::uint32_t));
    for (std::uint32_t i = 0; i < kCount; i += 511)
      EXPECT_EQ(copied[i], value * 1000u + i) << "the copy missed the host's write " << i;
    const std::vector<GpuTimer::Result> times = f.timer.resolve();
    std::vector<std::string> names;
    for (const GpuTimer::Result& t : times) {
      names.push_back(t.name);
      EXPECT_GE(t.ms, 0.0) << t.name;
    }
    EXPECT_EQ(names, (std::vector<std::string>{"test.fill", "test.host", "test.copy"}));
  }
  EXPECT_EQ(f.device.validation_errors(), 0u) << f.graph.dump();
}

// A host pass that needs no barrier (its buffer imported with no prior use, untouched by the
// frame's earlier passes) runs at once: the device pass declared before it has not been
// submitted yet when it runs (the host still sees the old contents of the buffer that pass
// fills), and a later device pass still sees what the host wrote. A second host pass that reads
// the fill waits for it as before, and every device pass runs exactly once (the fill's value is
// seen, the copy lands). The host G-buffer's trace (gbuffer.host) runs this way so it overlaps
// the frame in flight.
TEST(GraphHostPass, WithoutBarriersRunsAtOnceWithoutWaiting) {
  HostPassFixture f;
  Buffer fresh{f.device,
               {.size = kCount * sizeof(std::uint32_t),
                .usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                .memory = MemoryUsage::Readback,
                .name = "test.fresh"}};
  constexpr AccessState kAnyPriorUse{
      VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT | VK_PIPELINE_STAGE_2_HOST_BIT,
      VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT, VK_IMAGE_LAYOUT_UNDEFINED};
  std::memset(f.shared.mapped(), 0, kCount * sizeof(std::uint32_t));
  f.graph.begin_frame();
  struct One {
    BufferHandle buffer;
  };
  const BufferHandle filled = f.graph.add_pass<One>(
      "test.fill", PassKind::Transfer,
      [&](PassBuilder& p, One& d) {
        d.buffer = p.write(f.graph.import_buffer("test.shared", f.shared.handle(),
                                                 {f.shared.size()}, {.initial = kAnyPriorUse}),
                           Access::TransferDst);
        p.side_effect();
      },
      [](PassContext& ctx, const One& d) {
        vkCmdFillBuffer(ctx.cmd(), ctx.buffer(d.buffer), 0, VK_WHOLE_SIZE, 5u);
      }).buffer;
  std::uint32_t filled_before_host = 0;
  const BufferHandle written =
      f.graph
          .add_pass<One>(
              "test.host", PassKind::Host,
              [&](PassBuilder& p, One& d) {
                d.buffer = p.write(f.graph.import_buffer("test.fresh", fresh.handle(),
                                                         {fresh.size()}, {.initial = {}}),
                                   Access::HostReadWrite);
              },
              [&](PassContext&, const One&) {
                const auto* seen = reinterpret_cast<const std::uint32_t*>(f.shared.mapped());
                for (std::uint32_t i = 0; i < kCount; ++i) filled_before_host += seen[i] != 0u;
                auto* out = reinterpret_cast<std::uint32_t*>(fresh.mapped());
                for (std::uint32_t i = 0; i < kCount; ++i) out[i] = 3u * i + 1u;
              })
          .buffer;
  std::uint32_t fill_seen_by_waiting_host = 0;
  f.graph.add_pass<One>(
      "test.host_after_fill", PassKind::Host,
      [&](PassBuilder& p, One& d) {
        d.buffer = p.write(filled, Access::HostReadWrite);
        p.side_effect();
      },
      [&](PassContext&, const One&) {
        const auto* seen = reinterpret_cast<const std::uint32_t*>(f.shared.mapped());
        for (std::uint32_t i = 0; i < kCount; ++i) fill_seen_by_waiting_host += seen[i] == 5u;
      });
  struct Copy {
    BufferHandle from, to;
  };
  f.graph.add_pass<Copy>(
      "test.copy", PassKind::Transfer,
      [&](PassBuilder& p, Copy& d) {
        p.read(written, Access::TransferSrc);
        d.from = written;
        d.to = p.write(f.graph.import_buffer("test.result", f.result.handle(), {f.result.size()},
                                             {.initial = kAnyPriorUse}),
                       Access::TransferDst);
        p.side_effect();
      },
      [](PassContext& ctx, const Copy& d) {
        const VkBufferCopy region{0, 0, kCount * sizeof(std::uint32_t)};
        vkCmdCopyBuffer(ctx.cmd(), ctx.buffer(d.from), ctx.buffer(d.to), 1, &region);
      });
  f.graph.bake(f.executor.compile_options());
  f.timer.reset_on_host();
  f.device.submit_and_wait([&](VkCommandBuffer cmd) { f.executor.record(f.graph, cmd, &f.timer); });
  f.graph.end_frame();
  EXPECT_EQ(filled_before_host, 0u) << "the host pass waited for the fill before it";
  EXPECT_EQ(fill_seen_by_waiting_host, kCount) << "the waiting host pass missed the fill";
  const auto* shared = reinterpret_cast<const std::uint32_t*>(f.shared.mapped());
  const auto* copied = reinterpret_cast<const std::uint32_t*>(f.result.mapped());
  for (std::uint32_t i = 0; i < kCount; i += 511) {
    EXPECT_EQ(shared[i], 5u) << "the fill did not run";
    EXPECT_EQ(copied[i], 3u * i + 1u) << "the copy missed the host's write " << i;
  }
  // Reported in the order they ran: the barrier-free host pass first.
  std::vector<std::string> names;
  for (const GpuTimer::Result& t : f.timer.resolve()) names.push_back(t.name);
  EXPECT_EQ(names, (std::vector<std::string>{"test.host", "test.fill", "test.host_after_fill",
                                             "test.copy"}));
  EXPECT_EQ(f.device.validation_errors(), 0u) << f.graph.dump();
}

}  // namespace
}  // namespace lantern::runtime::graph
