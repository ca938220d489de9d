// A four-pass graph run on the Vulkan device (lavapipe): fill a buffer, transform it into an
// image, reduce the image into row sums, accumulate the sums with last frame's history and copy
// them to a host buffer. Checked on the CPU, over frames with and without history, clean under
// validation including synchronization validation, with synchronization2 and with v1 barriers.
// The transform reads the transient values, and the accumulation last frame's history, through
// the graph's texel views (PassContext::texel_view).
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "runtime/core/device.h"
#include "runtime/gpu/bindings.h"
#include "runtime/gpu/buffer.h"
#include "runtime/gpu/compute_pipeline.h"
#include "runtime/gpu/gpu_timer.h"
#include "runtime/gpu/shader_library.h"
#include "runtime/graph/graph_executor.h"

namespace lantern::runtime::graph {
namespace {

constexpr uint32_t kWidth = 64;
constexpr uint32_t kHeight = 48;
constexpr uint32_t kCount = kWidth * kHeight;

// What the four passes compute, on the CPU.
std::vector<uint32_t> expected_sums(uint32_t seed) {
  std::vector<uint32_t> sums(kHeight, 0);
  for (uint32_t y = 0; y < kHeight; ++y)
    for (uint32_t x = 0; x < kWidth; ++x) sums[y] += 2 * (3 * (y * kWidth + x) + seed) + 1;
  return sums;
}

struct Pipelines {
  ComputePipeline fill, transform, reduce, accumulate;
};

struct Push2 {
  uint32_t a, b;
};

struct Fixture {
  Device device{DeviceOptions{.validation = true, .sync_validation = true}};
  ShaderLibrary shaders;
  Pipelines pipes{
      ComputePipeline(device, shaders.load("tests/graph_fill.comp"), {.name = "test.fill"}),
      ComputePipeline(device, shaders.load("tests/graph_transform.comp"),
                      {.name = "test.transform"}),
      ComputePipeline(device, shaders.load("tests/graph_reduce.comp"), {.name = "test.reduce"}),
      ComputePipeline(device, shaders.load("tests/graph_accumulate.comp"),
                      {.name = "test.accumulate"})};
  Buffer readback{device,
                  {.size = kHeight * sizeof(uint32_t),
                   .usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                   .memory = MemoryUsage::Readback,
                   .name = "test.readback"}};
  GraphExecutor executor{device};
  GpuTimer timer{device, 16};
  RenderGraph graph;
  bool unused_pass_ran = false;

  // Declares and runs one frame; returns the host copy of the accumulated row sums.
  std::vector<uint32_t> frame(uint32_t seed, bool camera_cut = false) {
    graph.begin_frame();
    if (camera_cut) graph.invalidate_history();
    ImportInfo host_read;
    host_read.final = AccessState{VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT,
                                  VK_IMAGE_LAYOUT_UNDEFINED};
    const BufferHandle out =
        graph.import_buffer("test.readback", readback.handle(), {readback.size()}, host_read);
    const BufferHandle running =
        graph.create_history_buffer("test.running", {kHeight * sizeof(uint32_t)});
    const BufferHandle previous = graph.history(running);

    struct Values {
      BufferHandle values;
    };
    const Values& fill = graph.add_pass<Values>(
        "test.fill", PassKind::Compute,
        [&](PassBuilder& b, Values& d) {
          d.values = b.write(graph.create_buffer("test.values", {kCount * sizeof(uint32_t)}),
                             Access::StorageWrite);
        },
        [this, seed](PassContext& ctx, const Values& d) {
          pipes.fill.bind(
              ctx.cmd(),
              Bindings(pipes.fill).buffer("values", ctx.buffer(d.values), 0, VK_WHOLE_SIZE));
          pipes.fill.push_constants(ctx.cmd(), Push2{kCount, seed});
          pipes.fill.dispatch_threads(ctx.cmd(), kCount);
        });

    // Reads the values but nobody reads its output: culled, never executed.
    graph.add_pass<Values>(
        "test.unused", PassKind::Compute,
        [&](PassBuilder& b, Values& d) {
          b.read(fill.values, Access::StorageRead);
          d.values = b.write(graph.create_buffer("test.junk", {1024}), Access::StorageWrite);
        },
        [this](PassContext&, const Values&) { unused_pass_ran = true; });

    struct Img {
      ImageHandle image;
    };
    const Img& transform = graph.add_pass<Img>(
        "test.transform", PassKind::Compute,
        [&](PassBuilder& b, Img& d) {
          b.read(fill.values, Access::UniformTexelRead);
          d.image =
              b.write(graph.create_image("test.image", {{kWidth, kHeight, 1}, VK_FORMAT_R32_UINT}),
                      Access::StorageWrite);
        },
        [this, values = fill.values](PassContext& ctx, const Img& d) {
          pipes.transform.bind(
              ctx.cmd(), Bindings(pipes.transform)
                             .texel_buffer("values", ctx.texel_view(values))
                             .image_view("image", ctx.view(d.image), VK_IMAGE_LAYOUT_GENERAL));
          pipes.transform.push_constants(ctx.cmd(), Push2{kWidth, kHeight});
          pipes.transform.dispatch_threads(ctx.cmd(), kWidth, kHeight);
        });

    struct Sums {
      BufferHandle sums;
    };
    const Sums& reduce = graph.add_pass<Sums>(
        "test.reduce", PassKind::Compute,
        [&](PassBuilder& b, Sums& d) {
          b.read(transform.image, Access::StorageRead);
          d.sums = b.write(graph.create_buffer("test.sums", {kHeight * sizeof(uint32_t)}),
                           Access::StorageWrite);
        },
        [this, image = transform.image](PassContext& ctx, const Sums& d) {
          pipes.reduce.bind(ctx.cmd(),
                            Bindings(pipes.reduce)
                                .image_view("image", ctx.view(image), VK_IMAGE_LAYOUT_GENERAL)
                                .buffer("sums", ctx.buffer(d.sums), 0, VK_WHOLE_SIZE));
          pipes.reduce.push_constants(ctx.cmd(), Push2{kWidth, kHeight});
          pipes.reduce.dispatch_threads(ctx.cmd(), kHeight);
        });

    struct Acc {
      BufferHandle sums, previous, running, out;
    };
    graph.add_pass<Acc>(
        "test.accumulate", PassKind::Compute,
        [&](PassBuilder& b, Acc& d) {
          d.sums = reduce.sums;
          d.previous = previous;
          b.read(reduce.sums, Access::StorageRead);
          // Without history the sums stand in for `previous` (not read): a texel read too.
          b.read(previous ? previous : reduce.sums, Access::UniformTexelRead);
          d.running = b.write(running, Access::StorageWrite);
          d.out = b.write(out, Access::StorageWrite);
        },
        [this](PassContext& ctx, const Acc& d) {
          // Without history the shader ignores `previous`; bind the sums' view there (declared,
          // same size).
          const VkBufferView previous_view =
              d.previous ? ctx.texel_view(d.previous) : ctx.texel_view(d.sums);
          pipes.accumulate.bind(ctx.cmd(),
                                Bindings(pipes.accumulate)
                                    .buffer("sums", ctx.buffer(d.sums), 0, VK_WHOLE_SIZE)
                                    .texel_buffer("previous", previous_view)
                                    .buffer("running", ctx.buffer(d.running), 0, VK_WHOLE_SIZE)
                                    .buffer("readback", ctx.buffer(d.out), 0, VK_WHOLE_SIZE));
          pipes.accumulate.push_constants(ctx.cmd(), Push2{kHeight, d.previous ? 1u : 0u});
          pipes.accumulate.dispatch_threads(ctx.cmd(), kHeight);
        });

    graph.bake(executor.compile_options());
    device.submit_and_wait([&](VkCommandBuffer cmd) {
      timer.reset(cmd);
      executor.record(graph, cmd, &timer);
    });
    graph.end_frame();
    std::vector<uint32_t> result(kHeight);
    std::memcpy(result.data(), readback.mapped(), result.size() * sizeof(uint32_t));
    return result;
  }

  void run_frames_and_check() {
    ASSERT_TRUE(device.validation_enabled())
        << "validation layer missing: install vulkan-validationlayers";
    ASSERT_TRUE(device.sync_validation_enabled());
    const std::vector<uint32_t> sums = expected_sums(5);
    EXPECT_EQ(frame(5), sums) << "frame 1: no history";
    std::vector<uint32_t> twice(sums);
    for (uint32_t& v : twice) v *= 2;
    EXPECT_EQ(frame(5), twice) << "frame 2: running sum includes frame 1";
    const std::vector<uint32_t> other = expected_sums(11);
    EXPECT_EQ(frame(11, /*camera_cut=*/true), other) << "frame 3: camera cut drops history";
    std::vector<uint32_t> mixed(other);
    for (uint32_t y = 0; y < kHeight; ++y) mixed[y] += expected_sums(7)[y];
    EXPECT_EQ(frame(7), mixed) << "frame 4: history from frame 3";

    EXPECT_FALSE(unused_pass_ran);
    EXPECT_EQ(graph.compiled().culled.size(), 1u);
    EXPECT_GT(graph.compiled().alias_plan.saved(), 0u) << graph.dump();
    const auto timings = timer.resolve();
    std::vector<std::string> names;
    for (const auto& t : timings) names.push_back(t.name);
    EXPECT_EQ(names, (std::vector<std::string>{"test.fill", "test.transform", "test.reduce",
                                               "test.accumulate"}));
    EXPECT_EQ(device.validation_errors(), 0u) << graph.dump();
  }
};

TEST(GraphGpu, FourPassesWithHistoryAreCorrectAndSyncClean) {
  Fixture f;
  ASSERT_TRUE(f.executor.synchronization2());
  f.run_frames_and_check();
}

TEST(GraphGpu, Vulkan10BarriersAreAlsoSyncClean) {
  Fixture f;
  f.executor.use_synchronization2(false);
  f.run_frames_and_check();
}

}  // namespace
}  // namespace lantern::runtime::graph
