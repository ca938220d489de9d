// The scene's device buffers and their per-frame update from a FrameSnapshot.
//
// Static data (vertices, indices, materials, BVH triangles) is uploaded once at construction and
// imported read-only into every frame's graph. Per frame, update() applies the snapshot on the
// CPU — instance transforms (with previous transforms; the TLAS is rebuilt only when a transform
// changed), emissive triangles of moved or re-scaled instances re-extracted in world space,
// analytic lights, the light table's stable ids, prev->current remap and alias table — and
// add_upload_pass() adds `scene.upload`, a Transfer pass copying what changed from a host-visible
// staging ring (one staging buffer per frame in flight, plus one) into the device buffers. No
// barrier is recorded outside the graph; buffers that grow are retired after kRetireFrames.
//
// Shader names bind() sets, when (and only when) the pipeline declares them:
//   frame_constants (FrameConstants), scene_vertices, scene_indices, scene_materials,
//   scene_instances (GpuInstance), scene_lights (GpuLight), light_alias (AliasEntry),
//   light_previous_to_current (uint per previous-frame light: current index or kInvalidLight),
//   BvhHeaderBuffer, BvhNodeBuffer, BvhTriangleBuffer, BvhInstanceBuffer.
// Never-empty buffers: an empty array is uploaded as one zeroed element.
#pragma once

#include <array>
#include <cstdint>
#include <deque>
#include <memory>
#include <vector>

#include "engine/world/frame_snapshot.h"
#include "lighting/frame/frame_inputs.h"
#include "lighting/scene/scene_data.h"
#include "runtime/gpu/bindings.h"
#include "runtime/gpu/buffer.h"
#include "runtime/graph/render_graph.h"

namespace lantern::runtime {
class Device;
}

namespace lantern::lighting {

// What the last update() did and cost (CPU).
struct SceneUpdateStats {
  double cpu_ms = 0.0;       // whole update()
  double instance_ms = 0.0;  // transforms + TLAS rebuild
  double light_ms = 0.0;     // emitter extraction + light table (ids, remap, alias)
  std::uint32_t moved_instances = 0;
  std::uint32_t reextracted_instances = 0;  // emissive instances whose triangles were rebuilt
  std::uint32_t reextracted_triangles = 0;
  bool tlas_rebuilt = false;
  bool lights_changed = false;
  bool alias_rebuilt = false;
  std::uint64_t upload_bytes = 0;  // bytes scene.upload copied (set by add_upload_pass)
};

class GpuScene {
 public:
  // Builds the scene records of `level` and uploads them (blocking: setup time). Throws
  // lantern::InputError on bad level data.
  GpuScene(runtime::Device& device, std::shared_ptr<const Level> level);
  ~GpuScene();
  GpuScene(const GpuScene&) = delete;
  GpuScene& operator=(const GpuScene&) = delete;

  // Applies a frame's snapshot on the CPU (see the file comment). InputError when the snapshot
  // names an instance or mesh the level does not have.
  void update(const FrameSnapshot& snapshot);
  // This frame's constants (frame_constants.h builds them); uploaded by the next scene.upload.
  void set_frame_constants(const gpu::FrameConstants& constants);

  // Imports every scene buffer into `graph` (version 0: the contents before scene.upload; static
  // buffers read-only).
  [[nodiscard]] SceneHandles import(runtime::graph::RenderGraph& graph) const;
  // scene.upload: copies what changed since the last upload; returns the handles after it (what
  // integrators read). Call once per graph frame, after update() / set_frame_constants().
  [[nodiscard]] SceneHandles add_upload_pass(runtime::graph::RenderGraph& graph,
                                             const SceneHandles& imported);

  // Binds the scene buffers the pipeline declares, by the names listed above.
  void bind(runtime::Bindings& bindings) const;

  // Lights in the alias table (0 when no light has power: nothing can be sampled).
  std::uint32_t light_count() const;
  std::uint32_t light_record_count() const {
    return static_cast<std::uint32_t>(data_.lights.lights().size());
  }
  // Entries of light_previous_to_current (last frame's light count).
  std::uint32_t previous_light_count() const { return static_cast<std::uint32_t>(remap_.size()); }
  std::uint32_t instance_count() const {
    return static_cast<std::uint32_t>(data_.instances.size());
  }
  std::uint32_t emissive_triangles() const { return data_.emissive_triangles; }
  float scene_radius() const { return scene_radius_; }
  std::uint64_t bytes() const;

  const Level& level() const { return *level_; }
  const SceneData& data() const { return data_; }
  const std::vector<std::uint32_t>& light_previous_to_current() const { return remap_; }
  const SceneUpdateStats& last_update() const { return stats_; }

  static constexpr std::uint32_t kStagingSlots = 3;  // frames in flight (2) + 1
  static constexpr std::uint64_t kRetireFrames = 3;

  enum Slot : std::uint32_t {
    kFrameConstants,
    kVertices,
    kIndices,
    kMaterials,
    kInstances,
    kLights,
    kAlias,
    kBvhHeader,
    kBvhNodes,
    kBvhTriangles,
    kBvhInstances,
    kRemap,
    kSlotCount
  };

  // The device buffer behind a slot (tests, debugging; valid until the next update()).
  const runtime::Buffer& device_buffer(Slot slot) const { return arrays_[slot].buffer; }

 private:
  struct DeviceArray {
    runtime::Buffer buffer;
    bool read_only = false;
    // Pending upload: byte ranges [begin, end) of the CPU array (merged at upload).
    std::vector<std::pair<std::uint64_t, std::uint64_t>> dirty;
  };
  struct EmissiveInstance {
    std::uint32_t instance = 0;  // Level instance index
    std::uint32_t first = 0;     // first emitter in emitters_
    std::uint32_t count = 0;
    glm::mat4 world{1.0f};
    float scale = 1.0f;
    glm::vec3 radiance{0.0f};  // material emission at scale 1
  };

  std::span<const std::byte> cpu_bytes(Slot slot) const;
  void mark_dirty(Slot slot, std::uint64_t begin, std::uint64_t end);
  void mark_all_dirty(Slot slot);
  // Grows the device buffer of `slot` to hold its CPU array (retiring the old one).
  void ensure_capacity(Slot slot);
  void update_instances(const FrameSnapshot& snapshot);
  void update_lights(const FrameSnapshot& snapshot);

  runtime::Device& device_;
  std::shared_ptr<const Level> level_;
  SceneData data_;
  float scene_radius_ = 1.0f;
  gpu::FrameConstants constants_{};
  std::vector<std::uint32_t> remap_;    // previous light -> current
  std::vector<LightEmitter> emitters_;  // triangles (instance order), then analytic lights
  std::uint32_t triangle_emitters_ = 0;
  std::vector<EmissiveInstance> emissive_;
  std::vector<BvhInstanceDesc> bvh_descs_;
  std::array<DeviceArray, kSlotCount> arrays_;
  std::array<runtime::Buffer, kStagingSlots> staging_;
  std::deque<std::pair<std::uint64_t, runtime::Buffer>> retired_;
  std::uint64_t uploads_ = 0;  // scene.upload passes added so far
  SceneUpdateStats stats_;
};

}  // namespace lantern::lighting
