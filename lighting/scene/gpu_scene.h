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
// The buffers are the rows of lighting/scene/scene_buffers.h (one table: slot, graph name, shader
// name, texel view, access, source); passes read them through the SceneHandles import() and
// add_upload_pass() return.
// Never-empty buffers: an empty array is uploaded as one zeroed element.
//
// Ray-query visibility (constructed with VisibilityBackend::RayQuery): a RayQueryScene builds a
// BLAS per mesh and the TLAS at load; when an instance moves, the next add_upload_pass also adds
// `scene.tlas_build` (a graph pass after scene.upload: host-written instance records of this
// upload's ring slot -> TLAS), and the handles it returns carry the TLAS at kSceneTlas.
//
// Host visibility (VisibilityBackend::Host): a HostVisibility builds Embree's scene at load and
// moves its instances in update(); the BVH is built as for the BVH backend (every other ray).
//
// Environment: the level's map (if any) is loaded once (EnvironmentDistribution) and its tables
// uploaded with the static data; without one a black 1-texel stand-in (size.z = 0, params.z = 0)
// is bound. The probability that a light sample picks the environment (env header params.x,
// environment_selection_probability of the map's power proxy against the alias table's total
// power) is recomputed whenever the lights change and uploaded by the same scene.upload as the
// alias table, so each frame's selection pdfs match the table they sample (flickering lights
// stay unbiased).
#pragma once

#include <array>
#include <cstdint>
#include <deque>
#include <memory>
#include <optional>
#include <vector>

#include "engine/world/frame_snapshot.h"
#include "lighting/frame/frame_inputs.h"
#include "lighting/lights/environment_map.h"
#include "lighting/scene/scene_data.h"
#include "lighting/visibility/visibility_backend.h"
#include "runtime/gpu/buffer.h"
#include "runtime/gpu/buffer_view.h"
#include "runtime/graph/render_graph.h"
#include "runtime/runtime_fwd.h"

namespace lantern::lighting {

class RayQueryScene;
class HostVisibility;

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
  // `visibility` RayQuery also builds the ray-query BLASes and TLAS (the device must have ray
  // query: lantern::InputError otherwise).
  GpuScene(runtime::Device& device, std::shared_ptr<const Level> level,
           VisibilityBackend visibility = VisibilityBackend::Bvh);
  ~GpuScene();
  GpuScene(const GpuScene&) = delete;
  GpuScene& operator=(const GpuScene&) = delete;

  // Applies a frame's snapshot on the CPU (see the file comment). InputError when the snapshot
  // names an instance or mesh the level does not have.
  void update(const FrameSnapshot& snapshot);
  // This frame's constants (frame_constants.h builds them); uploaded by the next scene.upload.
  void set_frame_constants(const gpu::FrameConstants& constants);
  const gpu::FrameConstants& frame_constants() const { return constants_; }

  // Imports every scene buffer into `graph` (version 0: the contents before scene.upload; static
  // buffers read-only).
  [[nodiscard]] SceneHandles import(runtime::graph::RenderGraph& graph) const;
  // scene.upload: copies what changed since the last upload (and, for ray query, scene.tlas_build
  // rebuilds the TLAS when instances moved); returns the handles after them (what integrators
  // read). Call once per graph frame, after update() / set_frame_constants().
  [[nodiscard]] SceneHandles add_upload_pass(runtime::graph::RenderGraph& graph,
                                             const SceneHandles& imported);

  // Lights in the alias table (0 when no light has power: nothing can be sampled).
  std::uint32_t light_count() const;
  std::uint32_t light_record_count() const {
    return static_cast<std::uint32_t>(data_.lights.lights().size());
  }
  // Entries of light_previous_to_current (last frame's light count).
  std::uint32_t previous_light_count() const { return static_cast<std::uint32_t>(remap_.size()); }
  // Whether light_previous_to_current is the identity (every light kept its index since last
  // frame): the shaders then skip reading it (FrameConstants history.y).
  bool light_remap_is_identity() const { return remap_is_identity_; }
  std::uint32_t instance_count() const {
    return static_cast<std::uint32_t>(data_.instances.size());
  }
  std::uint32_t emissive_triangles() const { return data_.emissive_triangles; }
  float scene_radius() const { return scene_radius_; }
  // Participating media (scene_volumes records); 0 without volumes.
  std::uint32_t volume_count() const { return static_cast<std::uint32_t>(data_.volumes.size()); }
  // The environment header as uploaded by the next scene.upload (the stand-in's when the level
  // has no map); params.x is the environment's light-selection probability.
  const gpu::GpuEnvironment& environment() const { return env_header_; }
  // The level's environment map, or nullptr when it has none.
  const EnvironmentDistribution* environment_map() const { return env_ ? &*env_ : nullptr; }
  std::uint64_t bytes() const;

  VisibilityBackend visibility() const {
    if (host_) return VisibilityBackend::Host;
    return ray_query_ ? VisibilityBackend::RayQuery : VisibilityBackend::Bvh;
  }
  // Embree's scene of the host backend (built with VisibilityBackend::Host for a level it
  // supports; nullptr otherwise: the frame's shadow rays then stay on the compute BVH).
  HostVisibility* host_visibility() const { return host_.get(); }
  const Level& level() const { return *level_; }
  const SceneData& data() const { return data_; }
  const std::vector<std::uint32_t>& light_previous_to_current() const { return remap_; }
  const SceneUpdateStats& last_update() const { return stats_; }

  static constexpr std::uint32_t kStagingSlots = 3;  // frames in flight (2) + 1
  static constexpr std::uint64_t kRetireFrames = 3;

  // The device buffer behind a slot (tests, debugging; valid until the next update()).
  // `slot`: a gpu::kScene* constant (shared/scene_bindings.h).
  const runtime::Buffer& device_buffer(std::uint32_t slot) const { return arrays_[slot].buffer; }

 private:
  struct DeviceArray {
    runtime::Buffer buffer;
    runtime::BufferView texels;  // rgba32ui view (rows with a texel_name only)
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

  struct Copy {
    std::uint32_t slot;
    std::vector<VkBufferCopy> regions;
  };
  std::span<const std::byte> cpu_bytes(std::uint32_t slot) const;
  // scene.upload's copies from `staging`, and scene.tlas_build (both write the handles in `out`).
  void add_copy_pass(runtime::graph::RenderGraph& graph, const runtime::Buffer& staging,
                     const std::vector<Copy>& copies, SceneHandles& out);
  void add_tlas_build_pass(runtime::graph::RenderGraph& graph, std::uint32_t ring_slot,
                           SceneHandles& out);
  void mark_dirty(std::uint32_t slot, std::uint64_t begin, std::uint64_t end);
  void mark_all_dirty(std::uint32_t slot);
  // Grows the device buffer of `slot` to hold its CPU array (retiring the old one).
  void ensure_capacity(std::uint32_t slot);
  void update_instances(const FrameSnapshot& snapshot);
  void update_lights(const FrameSnapshot& snapshot);
  void update_volumes(const FrameSnapshot& snapshot);
  // Recomputes the environment's selection probability against the alias table's power; marks
  // the header dirty when it changed.
  void update_environment_probability();

  runtime::Device& device_;
  std::shared_ptr<const Level> level_;
  SceneData data_;
  float scene_radius_ = 1.0f;
  gpu::FrameConstants constants_{};
  std::vector<std::uint32_t> remap_;    // previous light -> current
  bool remap_is_identity_ = false;      // remap_ is the identity over the current lights
  std::vector<LightEmitter> emitters_;  // triangles (instance order), then analytic lights
  std::uint32_t triangle_emitters_ = 0;
  std::vector<EmissiveInstance> emissive_;
  std::vector<BvhInstanceDesc> bvh_descs_;
  std::array<DeviceArray, gpu::kSceneBufferCount> arrays_;
  SceneBufferSources sources_;  // the rows' CPU arrays (filled once at construction)
  std::array<runtime::Buffer, kStagingSlots> staging_;
  struct Retired {
    std::uint64_t upload = 0;  // uploads_ when it was retired
    runtime::Buffer buffer;
    runtime::BufferView texels;  // destroyed before the buffer
  };
  std::deque<Retired> retired_;
  // Environment: the level's map (nullopt: none, the stand-in arrays below are uploaded).
  std::optional<EnvironmentDistribution> env_;
  gpu::GpuEnvironment env_header_{};
  double env_power_ = 0.0;
  std::vector<gpu::vec4> env_dummy_texels_;
  std::vector<gpu::AliasEntry> env_dummy_alias_;
  std::uint64_t uploads_ = 0;  // scene.upload passes added so far
  std::unique_ptr<RayQueryScene> ray_query_;  // RayQuery only
  std::unique_ptr<HostVisibility> host_;      // Host only
  bool tlas_dirty_ = false;                   // an instance moved since the last TLAS build
  SceneUpdateStats stats_;
};

}  // namespace lantern::lighting
