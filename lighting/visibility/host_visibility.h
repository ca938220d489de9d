// The host visibility backend (VisibilityBackend::Host): on a CPU Vulkan device, Intel Embree on
// the host answers the frame's one shadow ray per pixel. On night_market's shadow rays it traces
// 5-7x faster than lavapipe runs the compute BVH on the same two cores (visibility_bench: "host"
// against "texel"), because Embree is built for the CPU's SIMD units, while lavapipe runs one
// shader invocation per SIMD lane and pays for every lane's divergent traversal.
//
// In the frame (render graph):
//   restir.shade / integrators.baseline   the "hostemit" shader variant shades every pixel as if
//       its shadow ray got through and writes the ray (shared/host_visibility.h) into the
//       mapped ray buffer
//   visibility.host   a PassKind::Host pass: the executor submits what came before, waits, and
//       this traces the records in place (rtcOccluded1M over Embree's RTCRay layout: zero copy)
//   restir.shade_occluded / integrators.baseline_occluded   the "hostresolve" variant rewrites
//       the pixels whose ray was blocked
// restir.initial's BSDF candidates (closest hits) go the same way through a second buffer:
//   restir.initial_rays   the "closestemit" variant writes each pixel's BSDF candidate rays
//       (shared/host_visibility.h's HostClosestRay: Embree's RTCRayHit layout)
//   visibility.host_closest   a host pass: rtcIntersect1M in place, each hit named as the compute
//       BVH names it (instance, triangle of its mesh, barycentrics)
//   restir.initial   the "closestresolve" variant reads the hits instead of tracing
// Every other ray (the reference's and the media's closest hits, restir.initial's optional
// shadow ray) stays on the compute BVH, which the scene keeps building.
//
// The scene: exactly the instances SceneBvh merges (fixed, opaque, within its triangle cap) form
// one world-space triangle geometry, so a ray pays for no overlapping instance boxes (README: two
// levels cost even Embree 5-7x on night_market); each other instance is an Embree instance of its
// mesh's scene, moved per frame. When the BVH takes a fixed instance that moved out of its merged
// tree, the merged geometry follows (one rebuild).
//
// Each ray buffer is single per frame: a host pass waits for everything submitted before it
// (Device::submit_and_wait), which with a window's frames in flight means the previous frame
// has finished. That orders its reads of the buffer before this frame's host writes, and it
// leaves one frame in flight while host visibility is on.
// Alpha-tested materials need the texture cutout at each hit, which only the shaders evaluate:
// supports() is false for such levels and the scene then keeps the compute BVH.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "lighting/bvh/scene_bvh.h"
#include "lighting/visibility/visibility_backend.h"
#include "runtime/gpu/buffer.h"
#include "runtime/graph/render_graph.h"
#include "runtime/runtime_fwd.h"
#include "shared/host_visibility.h"
#include "shared/scene.h"

namespace lantern::lighting {

class HostVisibility {
 public:
  // Whether the host can answer every shadow ray of these instances (none alpha-tested).
  static bool supports(std::span<const BvhInstanceDesc> instances);
  // Whether a frame on `backend` has host visibility for these instances: the one rule GpuScene
  // builds the Embree scene by, `lantern info` reports and --set gbuffer=host checks.
  static bool answers(VisibilityBackend backend, std::span<const BvhInstanceDesc> instances) {
    return backend == VisibilityBackend::Host && supports(instances);
  }

  // Builds Embree's scene over `bvh`'s meshes placed by `instances` (as given to
  // bvh.set_instances). lantern::RuntimeError naming Embree's error when it fails;
  // lantern::InputError when an instance is alpha-tested (see supports()).
  HostVisibility(runtime::Device& device, const SceneBvh& bvh,
                 std::span<const BvhInstanceDesc> instances);
  ~HostVisibility();
  HostVisibility(const HostVisibility&) = delete;
  HostVisibility& operator=(const HostVisibility&) = delete;

  // Per frame, after the instances moved: moves their Embree instances (and takes a fixed
  // instance that moved out of the merged geometry).
  void update(std::span<const BvhInstanceDesc> instances);

  // Traces every record in place on all host threads: tfar = -infinity where something blocks
  // the segment; records without an active ray (tnear > tfar) are left as they are. Returns how
  // many records held an active ray.
  std::size_t trace(std::span<gpu::HostShadowRay> rays) const;
  // Records that held an active ray in the last visibility.host pass (what `lantern bench` divides by
  // the pass's time for the host's rays per second).
  std::size_t last_traced() const { return last_traced_; }

  // Closest hits of every record in place on all host threads (shared/host_visibility.h's
  // HostClosestRay; only the ray part is read, the hit is reset first): instance (kNoInstance on
  // a miss), triangle of the instance's mesh, barycentrics and ray.tfar = the hit distance;
  // inactive records read as misses. Returns how many records held an active ray.
  std::size_t trace_closest(std::span<gpu::HostClosestRay> rays) const;
  // Records that held an active ray in the last visibility.host_closest pass.
  std::size_t last_closest_traced() const { return last_closest_traced_; }

  // The frame's ray buffer (at least `slots` records; host-visible, mapped), imported into
  // `graph` as "visibility.host_rays". Grows (after the device is idle) when a frame needs more.
  [[nodiscard]] runtime::graph::BufferHandle import_rays(runtime::graph::RenderGraph& graph,
                                                         std::uint32_t slots);
  // visibility.host: traces the first `slots` records of `rays` (import_rays' buffer, written by
  // an emit pass) in place; returns its new version for the resolve pass.
  [[nodiscard]] runtime::graph::BufferHandle add_trace_pass(runtime::graph::RenderGraph& graph,
                                                            runtime::graph::BufferHandle rays,
                                                            std::uint32_t slots);

  // The whole sequence for a pass that asks one shadow ray per slot: imports the ray buffer,
  // lets `emit` add the pass writing it (it returns the buffer's new version), adds
  // visibility.host; returns the traced buffer for the resolve pass to read.
  [[nodiscard]] runtime::graph::BufferHandle add_shadow_rays(
      runtime::graph::RenderGraph& graph, std::uint32_t slots,
      const std::function<runtime::graph::BufferHandle(runtime::graph::BufferHandle)>& emit);

  // The same for closest-hit rays: imports the closest-hit ray buffer
  // ("visibility.host_closest_rays", at least `slots` HostClosestRay records), lets `emit` add the
  // pass writing them, adds visibility.host_closest (trace_closest); returns the traced buffer
  // for the pass that reads the hits.
  [[nodiscard]] runtime::graph::BufferHandle add_closest_rays(
      runtime::graph::RenderGraph& graph, std::uint32_t slots,
      const std::function<runtime::graph::BufferHandle(runtime::graph::BufferHandle)>& emit);

  // Primary visibility (GBufferMethod::Host): per pixel of a width x height frame, row-major, the
  // closest triangle along the camera ray through its raster sample (pixel + 0.5 + the frame's
  // jitter; shared/gbuffer.h's gbuffer_camera_ray, near to far plane) as (instance, triangle of
  // the instance's mesh), or (kNoInstance, kNoInstance) where the ray meets nothing. On all host
  // threads; `hits` holds at least width x height records.
  void trace_primary(const gpu::FrameConstants& frame, std::uint32_t width, std::uint32_t height,
                     std::span<glm::uvec2> hits) const;
  // gbuffer.host: a host pass writing trace_primary's records for `frame` into the frame's hit
  // buffer ("gbuffer.host_hits", host-visible, mapped, one of a ring of three; grows when a frame
  // needs more); returns it for gbuffer.resolve to read. It needs nothing from the frame's
  // device passes, so it runs without waiting for them or for the frame still in flight.
  [[nodiscard]] runtime::graph::BufferHandle add_primary_pass(runtime::graph::RenderGraph& graph,
                                                              const gpu::FrameConstants& frame,
                                                              std::uint32_t width,
                                                              std::uint32_t height);

  unsigned threads() const { return threads_; }
  std::size_t merged_instances() const;
  double build_ms() const { return build_ms_; }
  std::string version() const;

 private:
  struct Embree;
  // A mapped buffer of ray records; grows (after the device is idle) when a frame needs more.
  struct RayBuffer {
    runtime::Buffer buffer;
    std::uint64_t capacity = 0;  // records
  };
  void build(const SceneBvh& bvh, std::span<const BvhInstanceDesc> instances);
  runtime::graph::BufferHandle import_ray_buffer(runtime::graph::RenderGraph& graph,
                                                 RayBuffer& rays, const char* name,
                                                 std::uint32_t slots, std::size_t record_size);
  // A host pass `name` that updates `rays` (an imported ray buffer) by running trace_records.
  static runtime::graph::BufferHandle add_host_pass(runtime::graph::RenderGraph& graph,
                                                    const char* name,
                                                    runtime::graph::BufferHandle rays,
                                                    std::function<void()> trace_records);

  runtime::Device& device_;
  const SceneBvh& bvh_;
  std::unique_ptr<Embree> embree_;
  unsigned threads_ = 1;
  double build_ms_ = 0.0;
  RayBuffer shadow_rays_;
  RayBuffer closest_rays_;
  std::vector<runtime::Buffer> hits_;  // the host G-buffer's ring (host_visibility.cpp kHitSlots)
  std::uint32_t hit_slot_ = 0;
  std::uint64_t hit_capacity_ = 0;
  std::size_t last_traced_ = 0;
  std::size_t last_closest_traced_ = 0;
};

}  // namespace lantern::lighting
