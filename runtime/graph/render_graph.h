// RenderGraph: a frame's passes declare what they read and write through typed versioned
// handles; bake() derives order, culling, barriers, layouts, lifetimes and memory aliasing.
// The object lives across frames: it owns history (last frame's versions) and its sync state.
//
//   graph.begin_frame();
//   auto& fill = graph.add_pass<FillData>("test.fill", PassKind::Compute,
//       [&](PassBuilder& b, FillData& d) {
//         d.out = b.write(graph.create_buffer("values", {4096}), Access::StorageWrite); },
//       [](PassContext& ctx, const FillData& d) { /* vkCmdDispatch ... ctx.buffer(d.out) */ });
//   graph.bake(); /* GraphExecutor records it */ graph.end_frame();
#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <unordered_map>

#include "runtime/graph/compiled_graph.h"
#include "runtime/graph/graph_compiler.h"
#include "runtime/graph/graph_decl.h"
#include "runtime/graph/history_tracker.h"
#include "runtime/graph/pass_context.h"

namespace lantern::runtime::graph {

class RenderGraph;

// Declares one pass's resource uses; only valid inside that pass's setup callback.
class PassBuilder {
 public:
  void read(BufferHandle h, Access access) { declare_read(h.index, h.version, access, false); }
  void read(ImageHandle h, Access access) { declare_read(h.index, h.version, access, true); }
  // Writes return the new version; the handle passed in must be the latest one.
  [[nodiscard]] BufferHandle write(BufferHandle h, Access access) {
    return {h.index, declare_write(h.index, h.version, access, false)};
  }
  [[nodiscard]] ImageHandle write(ImageHandle h, Access access) {
    return {h.index, declare_write(h.index, h.version, access, true)};
  }
  // Keeps the pass even if nobody reads its outputs (readback, present, debug output).
  void side_effect();

 private:
  friend class RenderGraph;
  PassBuilder(RenderGraph& graph, uint32_t pass) : graph_(graph), pass_(pass) {}
  void declare_read(uint32_t resource, uint32_t version, Access access, bool image);
  uint32_t declare_write(uint32_t resource, uint32_t version, Access access, bool image);
  bool check(uint32_t resource, Access access, bool image);

  RenderGraph& graph_;
  uint32_t pass_;
};

class RenderGraph {
 public:
  // Starts a new frame: forgets last frame's passes and transients, keeps history.
  void begin_frame();

  // Transient resources, created by the graph for this frame.
  [[nodiscard]] BufferHandle create_buffer(std::string_view name, const BufferDesc& desc);
  [[nodiscard]] ImageHandle create_image(std::string_view name, const ImageDesc& desc);
  // Persistent resources owned outside the graph.
  [[nodiscard]] BufferHandle import_buffer(std::string_view name, VkBuffer buffer,
                                           const BufferDesc& desc, const ImportInfo& info = {});
  [[nodiscard]] ImageHandle import_image(std::string_view name, VkImage image, VkImageView view,
                                         const ImageDesc& desc, const ImportInfo& info = {});
  // History resources: this frame's version (write it), kept for the next frame. Declare once
  // per frame under a stable name; a different description (resize) drops the history.
  [[nodiscard]] BufferHandle create_history_buffer(std::string_view name, const BufferDesc& desc);
  [[nodiscard]] ImageHandle create_history_image(std::string_view name, const ImageDesc& desc);
  // Last frame's version of a history resource; invalid on the first frame, after a resize,
  // after invalidate_history() and when last frame did not write it.
  [[nodiscard]] BufferHandle history(BufferHandle current) {
    return {history_of(current.index, false), 0};
  }
  [[nodiscard]] ImageHandle history(ImageHandle current) {
    return {history_of(current.index, true), 0};
  }
  // Camera cut: no pass gets history this frame (call before declaring history resources).
  void invalidate_history() { history_.invalidate_all(); }

  // Adds a pass: `setup(PassBuilder&, Data&)` runs now, `execute(PassContext&, const Data&)`
  // runs when the baked graph is recorded. Returns the pass data (handles for later passes).
  template <class Data, class Setup, class Execute>
  const Data& add_pass(std::string_view name, PassKind kind, Setup&& setup, Execute&& execute) {
    auto data = std::make_shared<Data>();
    PassBuilder builder = begin_pass(name, kind);
    setup(builder, *data);
    decl_.passes.back().execute = [data, run = std::forward<Execute>(execute)](PassContext& ctx) {
      run(ctx, *data);
    };
    return *data;
  }

  // Compiles the frame; throws RenderGraphError listing every misuse found.
  const CompiledGraph& bake(const CompileOptions& options = {});
  // Commits history writes and final sync states; call after the baked frame was recorded.
  void end_frame();

  [[nodiscard]] std::string dump() const;
  [[nodiscard]] const GraphDecl& decl() const { return decl_; }
  [[nodiscard]] const CompiledGraph& compiled() const { return compiled_; }
  // True between bake() and end_frame(): the frame may be recorded.
  [[nodiscard]] bool baked() const { return baked_; }
  [[nodiscard]] uint64_t frame() const { return history_.frame(); }

 private:
  friend class PassBuilder;
  struct HistoryRead {
    uint32_t slot = 0;
    bool valid = false;
    uint32_t resource = kInvalidIndex;  // HistoryPrevious resource once requested
  };

  PassBuilder begin_pass(std::string_view name, PassKind kind);
  uint32_t add_resource(ResourceDecl resource);
  uint32_t declare_history(std::string_view name, const HistoryDesc& desc);
  uint32_t history_of(uint32_t current, bool image);

  GraphDecl decl_;
  CompiledGraph compiled_;
  bool baked_ = false;
  bool compiled_this_frame_ = false;  // dump() stays available after end_frame()
  HistoryTracker history_;
  std::unordered_map<uint32_t, HistoryRead> history_reads_;  // by History resource index
};

}  // namespace lantern::runtime::graph
