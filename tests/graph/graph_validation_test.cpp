// Misuse rejected when the graph is baked, with messages naming the pass and the resource.
#include <gtest/gtest.h>

#include <cstdint>
#include <initializer_list>

#include "tests/graph/graph_test_util.h"

namespace lantern::runtime::graph {
namespace {

using test::Empty;
using test::kNoExecute;

struct Out {
  BufferHandle v;
};

// Bakes and checks the error message mentions every needle.
void expect_bake_error(RenderGraph& g, std::initializer_list<const char*> needles) {
  try {
    g.bake();
    ADD_FAILURE() << "bake() accepted an invalid graph";
  } catch (const RenderGraphError& e) {
    const std::string message = e.what();
    for (const char* needle : needles)
      EXPECT_NE(message.find(needle), std::string::npos) << "missing '" << needle << "' in:\n"
                                                         << message;
  }
}

TEST(GraphValidation, ReadOfANeverWrittenTransient) {
  RenderGraph g;
  const BufferHandle buf = g.create_buffer("restir.candidates", {64});
  g.add_pass<Empty>(
      "restir.spatial", PassKind::Compute,
      [&](PassBuilder& b, Empty&) {
        b.read(buf, Access::StorageRead);
        b.side_effect();
      },
      kNoExecute);
  expect_bake_error(g, {"restir.spatial", "restir.candidates", "before any pass wrote it"});
}

TEST(GraphValidation, WriteToAReadOnlyImport) {
  RenderGraph g;
  ImportInfo info;
  info.read_only = true;
  const BufferHandle lights = g.import_buffer("scene.lights", VK_NULL_HANDLE, {64}, info);
  g.add_pass<Out>(
      "test.bad", PassKind::Compute,
      [&](PassBuilder& b, Out& d) { d.v = b.write(lights, Access::StorageWrite); }, kNoExecute);
  expect_bake_error(g, {"test.bad", "scene.lights", "read-only"});
}

TEST(GraphValidation, WriteToHistoryOfLastFrame) {
  RenderGraph g;
  for (int frame = 0; frame < 2; ++frame) {
    g.begin_frame();
    const BufferHandle cur = g.create_history_buffer("restir.reservoirs", {256});
    const BufferHandle prev = g.history(cur);
    g.add_pass<Out>(
        "restir.temporal", PassKind::Compute,
        [&](PassBuilder& b, Out& d) {
          d.v = b.write(cur, Access::StorageWrite);
          if (prev) (void)b.write(prev, Access::StorageWrite);
        },
        kNoExecute);
    if (frame == 0) {
      g.bake();
      g.end_frame();
    } else {
      expect_bake_error(g,
                        {"restir.temporal", "restir.reservoirs", "read-only", "history-previous"});
    }
  }
}

TEST(GraphValidation, TwoWritersOfTheSameVersion) {
  RenderGraph g;
  const BufferHandle buf = g.create_buffer("gbuffer.ids", {64});
  g.add_pass<Out>(
      "test.first", PassKind::Compute,
      [&](PassBuilder& b, Out& d) { d.v = b.write(buf, Access::StorageWrite); }, kNoExecute);
  g.add_pass<Out>(
      "test.second", PassKind::Compute,
      [&](PassBuilder& b, Out& d) { d.v = b.write(buf, Access::StorageWrite); }, kNoExecute);
  expect_bake_error(g, {"two writers", "gbuffer.ids", "test.first", "test.second"});
}

TEST(GraphValidation, CycleThroughAStaleRead) {
  RenderGraph g;
  const BufferHandle sink = g.import_buffer("sink", VK_NULL_HANDLE, {16});
  const BufferHandle x = g.create_buffer("x", {64});
  const Out& a = g.add_pass<Out>(
      "test.a", PassKind::Compute,
      [&](PassBuilder& b, Out& d) { d.v = b.write(x, Access::StorageWrite); }, kNoExecute);
  struct Two {
    BufferHandle x, y;
  };
  const Two& bp = g.add_pass<Two>(
      "test.b", PassKind::Compute,
      [&](PassBuilder& b, Two& d) {
        d.x = b.write(a.v, Access::StorageReadWrite);
        d.y = b.write(g.create_buffer("y", {64}), Access::StorageWrite);
      },
      kNoExecute);
  // Reads y (after test.b) and x version 1 (before test.b overwrites it): impossible.
  g.add_pass<Empty>(
      "test.c", PassKind::Compute,
      [&](PassBuilder& b, Empty&) {
        b.read(bp.y, Access::StorageRead);
        b.read(a.v, Access::StorageRead);
        (void)b.write(sink, Access::StorageWrite);
      },
      kNoExecute);
  expect_bake_error(g, {"cycle", "test.b", "test.c"});
}

TEST(GraphValidation, ReadingOwnOutputIsACycle) {
  RenderGraph g;
  const BufferHandle x = g.create_buffer("x", {64});
  g.add_pass<Out>(
      "test.self", PassKind::Compute,
      [&](PassBuilder& b, Out& d) {
        d.v = b.write(x, Access::StorageWrite);
        b.read(d.v, Access::StorageRead);
        b.side_effect();
      },
      kNoExecute);
  expect_bake_error(g, {"test.self", "cycle"});
}

TEST(GraphValidation, AccessKindMustFitTheResource) {
  RenderGraph g;
  const BufferHandle buf = g.import_buffer("buf", VK_NULL_HANDLE, {64});
  g.add_pass<Empty>(
      "test.sample_buffer", PassKind::Graphics,
      [&](PassBuilder& b, Empty&) {
        b.read(buf, Access::Sampled);
        b.side_effect();
      },
      kNoExecute);
  expect_bake_error(g, {"test.sample_buffer", "buf", "sampled"});
}

TEST(GraphValidation, OneLayoutPerImagePerPass) {
  RenderGraph g;
  const ImageHandle img =
      g.import_image("img", VK_NULL_HANDLE, VK_NULL_HANDLE, {{8, 8, 1}, VK_FORMAT_R8G8B8A8_UNORM});
  g.add_pass<Empty>(
      "test.mixed", PassKind::Compute,
      [&](PassBuilder& b, Empty&) {
        b.read(img, Access::Sampled);
        (void)b.write(img, Access::StorageWrite);
      },
      kNoExecute);
  expect_bake_error(g, {"test.mixed", "img", "two layouts"});
}

TEST(GraphValidation, HistoryOfANonHistoryResource) {
  RenderGraph g;
  const BufferHandle buf = g.create_buffer("plain", {64});
  EXPECT_FALSE(g.history(buf).valid());
  expect_bake_error(g, {"plain", "not a history buffer"});
}

TEST(GraphValidation, ExecuteMayResolveOnlyDeclaredResources) {
  RenderGraph g;
  const BufferHandle declared = g.import_buffer("declared", VK_NULL_HANDLE, {64});
  const BufferHandle other = g.import_buffer("other", VK_NULL_HANDLE, {64});
  g.add_pass<Empty>(
      "test.sneaky", PassKind::Compute,
      [&](PassBuilder& b, Empty&) {
        b.read(declared, Access::StorageRead);
        b.side_effect();
      },
      kNoExecute);
  g.bake();
  const std::vector<PhysicalResource> physical(g.decl().resources.size());
  PassContext ctx(VK_NULL_HANDLE, g.decl(), 0, physical);
  EXPECT_NO_THROW((void)ctx.buffer(declared));
  EXPECT_THROW((void)ctx.buffer(other), RenderGraphError);
}

// A texel view only for a buffer the pass declared as a texel read (and that has one): a storage
// read of the same buffer, or an imported buffer without a view, is refused by name.
TEST(GraphValidation, TexelViewOnlyForADeclaredTexelRead) {
  RenderGraph g;
  const BufferHandle texels = g.import_buffer("texels", VK_NULL_HANDLE, {64});
  const BufferHandle storage = g.import_buffer("storage", VK_NULL_HANDLE, {64});
  g.add_pass<Empty>(
      "test.fetch", PassKind::Compute,
      [&](PassBuilder& b, Empty&) {
        b.read(texels, Access::UniformTexelRead);
        b.read(storage, Access::StorageRead);
        b.side_effect();
      },
      kNoExecute);
  g.bake();
  std::vector<PhysicalResource> physical(g.decl().resources.size());
  const VkBufferView view = reinterpret_cast<VkBufferView>(std::uintptr_t{0x1234});
  physical[texels.index].texel_view = view;
  physical[storage.index].texel_view = view;
  PassContext ctx(VK_NULL_HANDLE, g.decl(), 0, physical);
  EXPECT_EQ(ctx.texel_view(texels), view);
  try {
    (void)ctx.texel_view(storage);
    ADD_FAILURE() << "a storage read got a texel view";
  } catch (const RenderGraphError& e) {
    EXPECT_NE(std::string(e.what()).find("'storage'"), std::string::npos) << e.what();
  }
  physical[texels.index].texel_view = VK_NULL_HANDLE;  // imported without a view
  EXPECT_THROW((void)ctx.texel_view(texels), RenderGraphError);
}

// Host passes use mapped buffers on the host, and only they do: a compute pass declaring a host
// access, a host pass declaring a shader access, and a host pass on a transient (device-local,
// unmapped) buffer are refused.
void expect_host_use_refused(PassKind kind, Access access, bool imported,
                             std::initializer_list<const char*> needles) {
  RenderGraph g;
  const BufferHandle rays = imported
                                ? g.import_buffer("visibility.host_rays", VK_NULL_HANDLE, {64})
                                : g.create_buffer("visibility.host_rays", {64});
  g.add_pass<Empty>(
      kind == PassKind::Host ? "visibility.host" : "restir.shade", kind,
      [&](PassBuilder& b, Empty&) {
        if (is_write(access)) {
          (void)b.write(rays, access);
        } else {
          b.read(rays, access);
        }
        b.side_effect();
      },
      kNoExecute);
  expect_bake_error(g, needles);
}

TEST(GraphValidation, HostAccessOnlyInHostPassesOnImportedBuffers) {
  expect_host_use_refused(PassKind::Compute, Access::HostReadWrite, true,
                          {"restir.shade", "visibility.host_rays", "host-read-write"});
  expect_host_use_refused(PassKind::Host, Access::StorageRead, true,
                          {"visibility.host", "host pass", "storage-read"});
  expect_host_use_refused(PassKind::Host, Access::HostReadWrite, false,
                          {"visibility.host", "visibility.host_rays", "imported"});
}

}  // namespace
}  // namespace lantern::runtime::graph
