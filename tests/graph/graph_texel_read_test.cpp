// Access::UniformTexelRead: a buffer read through a uniform texel buffer view (the BVH arrays the
// integrators fetch with texelFetch). Its synchronisation scope is SHADER_SAMPLED_READ in the
// pass's shader stages (synchronization2: UNIFORM_READ covers uniform buffers only), transients
// get UNIFORM_TEXEL_BUFFER usage, and images cannot be read this way.
#include <gtest/gtest.h>

#include "tests/graph/graph_test_util.h"

namespace lantern::runtime::graph {
namespace {

using test::barrier_before;
using test::Empty;
using test::kNoExecute;

TEST(GraphTexelRead, StateIsSampledReadInThePassShaderStages) {
  const AccessState compute = access_state(Access::UniformTexelRead, PassKind::Compute, false);
  EXPECT_EQ(compute.stages, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
  EXPECT_EQ(compute.access, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
  EXPECT_EQ(compute.layout, VK_IMAGE_LAYOUT_UNDEFINED);
  const AccessState graphics = access_state(Access::UniformTexelRead, PassKind::Graphics, false);
  EXPECT_EQ(graphics.stages,
            VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT);
  EXPECT_EQ(graphics.access, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
  EXPECT_EQ(buffer_usage(Access::UniformTexelRead), VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT);
  EXPECT_TRUE(is_read(Access::UniformTexelRead));
  EXPECT_FALSE(is_write(Access::UniformTexelRead));
  EXPECT_TRUE(allowed_on_buffer(Access::UniformTexelRead));
  EXPECT_FALSE(allowed_on_image(Access::UniformTexelRead));
  EXPECT_STREQ(access_name(Access::UniformTexelRead), "uniform-texel-read");
}

TEST(GraphTexelRead, UploadThenTexelReadGetsASampledReadBarrier) {
  RenderGraph g;
  const BufferHandle nodes = g.import_buffer("bvh_nodes", VK_NULL_HANDLE, {4096});
  struct H {
    BufferHandle v;
  };
  const H& up = g.add_pass<H>(
      "test.upload", PassKind::Transfer,
      [&](PassBuilder& b, H& d) { d.v = b.write(nodes, Access::TransferDst); }, kNoExecute);
  g.add_pass<Empty>(
      "test.trace", PassKind::Compute,
      [&](PassBuilder& b, Empty&) {
        b.read(up.v, Access::UniformTexelRead);
        b.side_effect();
      },
      kNoExecute);
  g.bake();
  const auto b = barrier_before(g, "test.trace", nodes.index);
  ASSERT_TRUE(b) << g.dump();
  EXPECT_NE(b->src.stages & VK_PIPELINE_STAGE_2_COPY_BIT, 0u);
  EXPECT_EQ(b->src.access, VK_ACCESS_2_TRANSFER_WRITE_BIT);
  EXPECT_EQ(b->dst.stages, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
  EXPECT_EQ(b->dst.access, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
  EXPECT_NE(g.dump().find("uniform-texel-read"), std::string::npos) << g.dump();
}

TEST(GraphTexelRead, StorageAndTexelReadsInOnePassMerge) {
  // A pass that binds the same buffer as a storage buffer and as a texel view (SceneHandles
  // declares both while some passes still read the BVH as storage buffers).
  RenderGraph g;
  const BufferHandle data = g.create_buffer("data", {1024});
  struct H {
    BufferHandle v;
  };
  const H& w = g.add_pass<H>(
      "test.produce", PassKind::Compute,
      [&](PassBuilder& b, H& d) { d.v = b.write(data, Access::StorageWrite); }, kNoExecute);
  g.add_pass<Empty>(
      "test.consume", PassKind::Compute,
      [&](PassBuilder& b, Empty&) {
        b.read(w.v, Access::StorageRead);
        b.read(w.v, Access::UniformTexelRead);
        b.side_effect();
      },
      kNoExecute);
  g.bake();
  const auto b = barrier_before(g, "test.consume", data.index);
  ASSERT_TRUE(b) << g.dump();
  EXPECT_EQ(b->src.access, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  EXPECT_EQ(b->dst.access,
            VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
  // The transient is created for both uses.
  const VkBufferUsageFlags usage = g.decl().resources[data.index].buffer_usage;
  EXPECT_NE(usage & VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT, 0u);
  EXPECT_NE(usage & VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, 0u);
}

TEST(GraphTexelRead, ImagesCannotBeReadAsTexelBuffers) {
  RenderGraph g;
  const ImageHandle img =
      g.import_image("img", VK_NULL_HANDLE, VK_NULL_HANDLE, {{8, 8, 1}, VK_FORMAT_R8G8B8A8_UNORM});
  g.add_pass<Empty>(
      "test.texel_image", PassKind::Compute,
      [&](PassBuilder& b, Empty&) {
        b.read(img, Access::UniformTexelRead);
        b.side_effect();
      },
      kNoExecute);
  try {
    g.bake();
    ADD_FAILURE() << "bake() accepted a texel read of an image";
  } catch (const RenderGraphError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("test.texel_image"), std::string::npos) << message;
    EXPECT_NE(message.find("uniform-texel-read"), std::string::npos) << message;
  }
}

}  // namespace
}  // namespace lantern::runtime::graph
