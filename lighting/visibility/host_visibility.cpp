// Embree's scene, the host pass and the ray buffer of the host visibility backend
// (host_visibility.h).
#include "lighting/visibility/host_visibility.h"

#include <embree3/rtcore.h>
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cstring>
#include <glm/gtc/type_ptr.hpp>
#include <thread>

#include "engine/core/error.h"
#include "lighting/scene/gpu_scene.h"
#include "runtime/core/device.h"
#include "shared/gbuffer.h"

namespace lantern::lighting {
namespace {

static_assert(sizeof(gpu::HostShadowRay) == sizeof(RTCRay), "HostShadowRay must be an RTCRay");
static_assert(offsetof(RTCRay, tfar) == offsetof(gpu::HostShadowRay, tfar));
static_assert(offsetof(RTCRay, mask) == offsetof(gpu::HostShadowRay, mask));
static_assert(sizeof(gpu::HostClosestRay) == sizeof(RTCRayHit),
              "HostClosestRay must be an RTCRayHit");
static_assert(offsetof(RTCRayHit, hit) == offsetof(gpu::HostClosestRay, ng_x));
static_assert(offsetof(RTCRayHit, hit.u) == offsetof(gpu::HostClosestRay, u));
static_assert(offsetof(RTCRayHit, hit.primID) == offsetof(gpu::HostClosestRay, primitive));
static_assert(offsetof(RTCRayHit, hit.geomID) == offsetof(gpu::HostClosestRay, instance));
static_assert(offsetof(RTCRayHit, hit.instID) == offsetof(gpu::HostClosestRay, instance_id));
static_assert(gpu::kNoInstance == RTC_INVALID_GEOMETRY_ID, "a miss reads the same to both");

// Rays handed to one rtcOccluded1M call: big enough for Embree's stream path to sort them into
// packets, small enough that two threads share the frame's rays evenly.
constexpr std::uint32_t kRaysPerChunk = 256;

// The host G-buffer's hit buffers: as many as the scene's staging slots (frames in flight + 1),
// so the slot a frame writes was last read by a frame that has finished.
constexpr std::uint32_t kHitSlots = GpuScene::kStagingSlots;

// A host buffer's state when a frame imports it: last frame's passes may still use it (a window
// keeps frames in flight), so this frame's first use orders after all of them.
runtime::graph::AccessState any_prior_use() {
  return {VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT | VK_PIPELINE_STAGE_2_HOST_BIT,
          VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT | VK_ACCESS_2_HOST_READ_BIT |
              VK_ACCESS_2_HOST_WRITE_BIT,
          VK_IMAGE_LAYOUT_UNDEFINED};
}

// Runs work(begin, count, context) over the records [0, total) in chunks of kRaysPerChunk on
// `threads` host threads (this one among them).
template <class Work>
void parallel_chunks(unsigned threads, std::size_t total, const Work& work) {
  std::atomic<std::size_t> next{0};
  auto worker = [&] {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    for (std::size_t begin = next.fetch_add(kRaysPerChunk); begin < total;
         begin = next.fetch_add(kRaysPerChunk)) {
      work(begin, static_cast<unsigned>(std::min<std::size_t>(kRaysPerChunk, total - begin)),
           context);
    }
  };
  std::vector<std::thread> pool;
  const std::size_t chunks = (total + kRaysPerChunk - 1) / kRaysPerChunk;
  for (unsigned t = 1; t < std::min<std::size_t>(threads, chunks); ++t) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();
}

bool alpha_tested(const BvhInstanceDesc& d) {
  return (d.flags & gpu::kBvhInstanceAlphaTested) != 0u;
}

// Whether instance i's triangles belong in the merged world-space geometry: exactly the BVH's
// merged set (its triangle cap, never a fixed instance that moved), empty meshes left out.
bool in_merged_geometry(const SceneBvh& bvh, std::span<const BvhInstanceDesc> instances,
                        std::size_t i) {
  return bvh.merged(i) && !bvh.mesh(instances[i].mesh).empty();
}

}  // namespace

struct HostVisibility::Embree {
  RTCDevice device = nullptr;
  // Two scenes, each ray asked of both (an occluded ray is inactive for the second): the fixed
  // instances' world-space triangles, never committed again while they stay put, and the other
  // instances (instance i has id i), committed when one moves. One scene holding both rebuilt
  // the merged triangles' tree at every commit (25 ms per frame on night_market); instancing the
  // merged scene beside the movers instead would put an instance level on every ray.
  RTCScene merged_scene = nullptr;
  RTCScene scene = nullptr;
  bool instanced = false;             // `scene` holds an instance
  std::vector<RTCScene> mesh_scenes;  // per mesh id, made when an instance needs it
  std::vector<bool> merged;           // per instance: in the merged world-space geometry
  // The merged geometry's triangles instance by instance: merged_first[k] is the first primID of
  // the k-th merged instance, merged_instance[k] its instance index (closest hits name theirs).
  std::vector<std::uint32_t> merged_first;
  std::vector<std::uint32_t> merged_instance;
  std::vector<glm::mat4> placed;      // per instanced instance: the transform Embree has

  ~Embree() {
    release_placed_scenes();
    for (RTCScene m : mesh_scenes)
      if (m != nullptr) rtcReleaseScene(m);
    if (device != nullptr) rtcReleaseDevice(device);
  }

  // The scenes that depend on the placement (the mesh scenes are object space: kept).
  void release_placed_scenes() {
    if (scene != nullptr) rtcReleaseScene(scene);
    scene = nullptr;
    if (merged_scene != nullptr) rtcReleaseScene(merged_scene);
    merged_scene = nullptr;
  }

  void check(const char* what) const {
    const RTCError error = rtcGetDeviceError(device);
    if (error != RTC_ERROR_NONE)
      throw RuntimeError(fmt::format("host visibility: Embree {} failed (RTCError {})", what,
                                     static_cast<int>(error)));
  }

  // A triangle geometry of `triangles` triangles and `vertices` vertices; fills its buffers.
  RTCGeometry new_triangles(std::size_t vertices, std::size_t triangles, float** positions,
                            unsigned** indices) const {
    RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    *positions = static_cast<float*>(rtcSetNewGeometryBuffer(
        geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), vertices));
    *indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
        geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), triangles));
    check("geometry buffers");
    return geometry;
  }

  // Closest hits of `count` records in place: the merged scene first, then the instances'
  // scene, which only takes hits nearer than the merged one's (tfar shrank to it) and names
  // them by instID. Then each hit is named as the compute BVH names it: geomID the scene
  // instance index (kNoInstance on a miss), primID the triangle of that instance's mesh.
  void intersect_and_name(RTCIntersectContext& context, RTCRayHit* records,
                          unsigned count) const {
    for (unsigned k = 0; k < count; ++k) {
      records[k].hit.geomID = RTC_INVALID_GEOMETRY_ID;
      records[k].hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    }
    if (merged_scene != nullptr)
      rtcIntersect1M(merged_scene, &context, records, count, sizeof(RTCRayHit));
    if (instanced) rtcIntersect1M(scene, &context, records, count, sizeof(RTCRayHit));
    for (unsigned k = 0; k < count; ++k) {
      RTCHit& h = records[k].hit;
      if (h.instID[0] != RTC_INVALID_GEOMETRY_ID) {
        h.geomID = h.instID[0];
      } else if (h.geomID != RTC_INVALID_GEOMETRY_ID) {
        // The last merged instance whose first primID is <= the hit's.
        const auto it = std::upper_bound(merged_first.begin(), merged_first.end(), h.primID);
        const std::size_t m = static_cast<std::size_t>(it - merged_first.begin()) - 1;
        h.geomID = merged_instance[m];
        h.primID -= merged_first[m];
      } else {
        h.primID = RTC_INVALID_GEOMETRY_ID;
      }
    }
  }

  RTCScene mesh_scene(const MeshBvh& mesh, std::uint32_t id) {
    if (mesh_scenes.at(id) != nullptr) return mesh_scenes[id];
    float* positions = nullptr;
    unsigned* indices = nullptr;
    RTCGeometry geometry =
        new_triangles(mesh.positions().size(), mesh.indices().size() / 3, &positions, &indices);
    std::memcpy(positions, mesh.positions().data(), mesh.positions().size() * sizeof(glm::vec3));
    std::memcpy(indices, mesh.indices().data(), mesh.indices().size() * sizeof(unsigned));
    rtcCommitGeometry(geometry);
    RTCScene s = rtcNewScene(device);
    rtcAttachGeometry(s, geometry);
    rtcReleaseGeometry(geometry);
    rtcCommitScene(s);
    check("mesh scene");
    mesh_scenes[id] = s;
    return s;
  }
};

bool HostVisibility::supports(std::span<const BvhInstanceDesc> instances) {
  return std::none_of(instances.begin(), instances.end(), alpha_tested);
}

HostVisibility::HostVisibility(runtime::Device& device, const SceneBvh& bvh,
                               std::span<const BvhInstanceDesc> instances)
    : device_(device), bvh_(bvh), embree_(std::make_unique<Embree>()) {
  if (!supports(instances)) {
    throw InputError(
        "host visibility: the level has alpha-tested materials, whose cutout only the shaders "
        "evaluate; use visibility=bvh");
  }
  threads_ = std::max(1u, std::thread::hardware_concurrency());
  const std::string config = fmt::format("threads={}", threads_);
  embree_->device = rtcNewDevice(config.c_str());
  if (embree_->device == nullptr) throw RuntimeError("host visibility: rtcNewDevice failed");
  build(bvh, instances);
}

HostVisibility::~HostVisibility() = default;

std::string HostVisibility::version() const {
  const auto v = rtcGetDeviceProperty(embree_->device, RTC_DEVICE_PROPERTY_VERSION);
  return fmt::format("Embree {}.{}.{}", v / 10000, (v / 100) % 100, v % 100);
}

std::size_t HostVisibility::merged_instances() const {
  return static_cast<std::size_t>(std::count(embree_->merged.begin(), embree_->merged.end(), true));
}

void HostVisibility::build(const SceneBvh& bvh, std::span<const BvhInstanceDesc> instances) {
  const auto start = std::chrono::steady_clock::now();
  Embree& e = *embree_;
  e.release_placed_scenes();
  e.mesh_scenes.resize(bvh.mesh_count(), nullptr);
  e.merged.assign(instances.size(), false);
  e.merged_first.clear();
  e.merged_instance.clear();
  e.placed.assign(instances.size(), glm::mat4(1.0f));
  e.scene = rtcNewScene(e.device);
  e.instanced = false;

  // The merged geometry: the triangles of the instances the BVH merged, in world space.
  std::size_t vertex_count = 0;
  std::size_t triangle_count = 0;
  for (std::size_t i = 0; i < instances.size(); ++i) {
    const BvhInstanceDesc& d = instances[i];
    if (!in_merged_geometry(bvh, instances, i)) continue;
    e.merged[i] = true;
    e.merged_first.push_back(static_cast<std::uint32_t>(triangle_count));
    e.merged_instance.push_back(static_cast<std::uint32_t>(i));
    vertex_count += bvh.mesh(d.mesh).positions().size();
    triangle_count += bvh.mesh(d.mesh).triangle_count();
  }
  if (triangle_count > 0) {
    float* positions = nullptr;
    unsigned* indices = nullptr;
    RTCGeometry geometry = e.new_triangles(vertex_count, triangle_count, &positions, &indices);
    std::size_t first_vertex = 0;
    for (std::size_t i = 0; i < instances.size(); ++i) {
      if (!e.merged[i]) continue;
      const MeshBvh& mesh = bvh.mesh(instances[i].mesh);
      for (const glm::vec3& p : mesh.positions()) {
        const glm::vec3 w = glm::vec3(instances[i].object_to_world * glm::vec4(p, 1.0f));
        std::memcpy(positions, &w, sizeof(w));
        positions += 3;
      }
      for (const std::uint32_t index : mesh.indices())
        *indices++ = static_cast<unsigned>(first_vertex + index);
      first_vertex += mesh.positions().size();
    }
    rtcCommitGeometry(geometry);
    e.merged_scene = rtcNewScene(e.device);
    rtcAttachGeometry(e.merged_scene, geometry);
    rtcReleaseGeometry(geometry);
    rtcCommitScene(e.merged_scene);
    e.check("merged geometry");
  }
  // Everything else is an instance of its mesh's scene.
  for (std::size_t i = 0; i < instances.size(); ++i) {
    const BvhInstanceDesc& d = instances[i];
    if (e.merged[i] || bvh.mesh(d.mesh).empty()) continue;
    RTCGeometry instance = rtcNewGeometry(e.device, RTC_GEOMETRY_TYPE_INSTANCE);
    rtcSetGeometryInstancedScene(instance, e.mesh_scene(bvh.mesh(d.mesh), d.mesh));
    rtcSetGeometryTransform(instance, 0, RTC_FORMAT_FLOAT4X4_COLUMN_MAJOR,
                            glm::value_ptr(d.object_to_world));
    rtcCommitGeometry(instance);
    rtcAttachGeometryByID(e.scene, instance, static_cast<unsigned>(i));
    rtcReleaseGeometry(instance);
    e.placed[i] = d.object_to_world;
    e.instanced = true;
  }
  e.check("instance geometry");
  rtcCommitScene(e.scene);
  e.check("scene build");
  build_ms_ =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

void HostVisibility::update(std::span<const BvhInstanceDesc> instances) {
  Embree& e = *embree_;
  if (instances.size() != e.placed.size()) {
    throw InputError(fmt::format("host visibility: {} instances, the scene was built with {}",
                                 instances.size(), e.placed.size()));
  }
  // The BVH's set_instances ran first: a fixed instance that moved has left its merged tree.
  bool rebuild = false;
  for (std::size_t i = 0; i < instances.size(); ++i) {
    rebuild = rebuild || e.merged[i] != in_merged_geometry(bvh_, instances, i);
  }
  if (rebuild) {
    build(bvh_, instances);
    return;
  }
  bool moved = false;
  for (std::size_t i = 0; i < instances.size(); ++i) {
    const BvhInstanceDesc& d = instances[i];
    if (e.merged[i] || d.object_to_world == e.placed[i] || bvh_.mesh(d.mesh).empty()) continue;
    RTCGeometry instance = rtcGetGeometry(e.scene, static_cast<unsigned>(i));
    rtcSetGeometryTransform(instance, 0, RTC_FORMAT_FLOAT4X4_COLUMN_MAJOR,
                            glm::value_ptr(d.object_to_world));
    rtcCommitGeometry(instance);
    e.placed[i] = d.object_to_world;
    moved = true;
  }
  if (moved) {
    rtcCommitScene(e.scene);
    e.check("scene update");
  }
}

std::size_t HostVisibility::trace(std::span<gpu::HostShadowRay> rays) const {
  RTCScene merged = embree_->merged_scene;
  RTCScene instances = embree_->instanced ? embree_->scene : nullptr;
  std::atomic<std::size_t> traced{0};
  parallel_chunks(threads_, rays.size(),
                  [&](std::size_t begin, unsigned count, RTCIntersectContext& context) {
                    std::size_t active = 0;
                    for (std::size_t i = begin; i < begin + count; ++i)
                      active += gpu::host_ray_active(rays[i]) ? 1u : 0u;
                    auto* chunk = reinterpret_cast<RTCRay*>(&rays[begin]);
                    if (merged != nullptr)
                      rtcOccluded1M(merged, &context, chunk, count, sizeof(RTCRay));
                    if (instances != nullptr)
                      rtcOccluded1M(instances, &context, chunk, count, sizeof(RTCRay));
                    traced += active;
                  });
  return traced;
}

std::size_t HostVisibility::trace_closest(std::span<gpu::HostClosestRay> rays) const {
  std::atomic<std::size_t> traced{0};
  parallel_chunks(threads_, rays.size(),
                  [&](std::size_t begin, unsigned count, RTCIntersectContext& context) {
                    std::size_t active = 0;
                    for (std::size_t i = begin; i < begin + count; ++i)
                      active += gpu::host_ray_active(rays[i].ray) ? 1u : 0u;
                    embree_->intersect_and_name(
                        context, reinterpret_cast<RTCRayHit*>(&rays[begin]), count);
                    traced += active;
                  });
  return traced;
}

runtime::graph::BufferHandle HostVisibility::import_ray_buffer(runtime::graph::RenderGraph& graph,
                                                               RayBuffer& rays, const char* name,
                                                               std::uint32_t slots,
                                                               std::size_t record_size) {
  slots = std::max(slots, 1u);
  if (slots > rays.capacity) {
    if (rays.capacity > 0) device_.wait_idle();  // the old buffer may still be read
    rays.buffer = runtime::Buffer(device_, {.size = VkDeviceSize{slots} * record_size,
                                            .usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                            .memory = runtime::MemoryUsage::Readback,
                                            .name = name});
    if (rays.buffer.mapped() == nullptr ||
        reinterpret_cast<std::uintptr_t>(rays.buffer.mapped()) % alignof(RTCRayHit) != 0) {
      throw RuntimeError(fmt::format("host visibility: {} is not mapped 16-byte aligned", name));
    }
    rays.capacity = slots;
  }
  return graph.import_buffer(name, rays.buffer.handle(), {rays.buffer.size()},
                             {.read_only = false, .initial = any_prior_use()});
}

runtime::graph::BufferHandle HostVisibility::import_rays(runtime::graph::RenderGraph& graph,
                                                         std::uint32_t slots) {
  return import_ray_buffer(graph, shadow_rays_, "visibility.host_rays", slots,
                           sizeof(gpu::HostShadowRay));
}

runtime::graph::BufferHandle HostVisibility::add_host_pass(
    runtime::graph::RenderGraph& graph, const char* name, runtime::graph::BufferHandle rays,
    std::function<void()> trace_records) {
  struct Data {
    runtime::graph::BufferHandle rays;
  };
  return graph
      .add_pass<Data>(
          name, runtime::graph::PassKind::Host,
          [&](runtime::graph::PassBuilder& b, Data& d) {
            d.rays = b.write(rays, runtime::graph::Access::HostReadWrite);
          },
          [trace_records = std::move(trace_records)](runtime::graph::PassContext&, const Data&) {
            trace_records();
          })
      .rays;
}

runtime::graph::BufferHandle HostVisibility::add_trace_pass(runtime::graph::RenderGraph& graph,
                                                            runtime::graph::BufferHandle rays,
                                                            std::uint32_t slots) {
  return add_host_pass(graph, "visibility.host", rays, [this, slots] {
    auto* records = reinterpret_cast<gpu::HostShadowRay*>(shadow_rays_.buffer.mapped());
    last_traced_ = trace(std::span(records, std::min<std::uint64_t>(slots, shadow_rays_.capacity)));
  });
}

runtime::graph::BufferHandle HostVisibility::add_closest_rays(
    runtime::graph::RenderGraph& graph, std::uint32_t slots,
    const std::function<runtime::graph::BufferHandle(runtime::graph::BufferHandle)>& emit) {
  const runtime::graph::BufferHandle written = emit(import_ray_buffer(
      graph, closest_rays_, "visibility.host_closest_rays", slots, sizeof(gpu::HostClosestRay)));
  return add_host_pass(graph, "visibility.host_closest", written, [this, slots] {
    auto* records = reinterpret_cast<gpu::HostClosestRay*>(closest_rays_.buffer.mapped());
    last_closest_traced_ =
        trace_closest(std::span(records, std::min<std::uint64_t>(slots, closest_rays_.capacity)));
  });
}

void HostVisibility::trace_primary(const gpu::FrameConstants& frame, std::uint32_t width,
                                   std::uint32_t height, std::span<glm::uvec2> hits) const {
  const std::size_t pixels = std::size_t{width} * height;
  if (hits.size() < pixels) {
    throw RuntimeError(fmt::format("host visibility: {} hit records for {}x{} pixels", hits.size(),
                                   width, height));
  }
  const glm::vec2 size(static_cast<float>(width), static_cast<float>(height));
  const glm::vec2 jitter(frame.jitter.x, frame.jitter.y);
  parallel_chunks(threads_, pixels, [&](std::size_t begin, unsigned count,
                                        RTCIntersectContext& context) {
    std::array<RTCRayHit, kRaysPerChunk> chunk;
    for (unsigned k = 0; k < count; ++k) {
      const std::size_t p = begin + k;
      const glm::vec2 point =
          glm::vec2(static_cast<float>(p % width), static_cast<float>(p / width)) + 0.5f + jitter;
      glm::vec3 origin;
      float far_t = 0.0f;
      const glm::vec3 direction =
          gpu::gbuffer_camera_ray(frame.inv_view_proj, point, size, origin, far_t);
      RTCRayHit& r = chunk[k];
      r.ray.org_x = origin.x;
      r.ray.org_y = origin.y;
      r.ray.org_z = origin.z;
      r.ray.tnear = 0.0f;
      r.ray.dir_x = direction.x;
      r.ray.dir_y = direction.y;
      r.ray.dir_z = direction.z;
      r.ray.time = 0.0f;
      r.ray.tfar = far_t;
      r.ray.mask = ~0u;
      r.ray.id = static_cast<unsigned>(k);
      r.ray.flags = 0;
    }
    embree_->intersect_and_name(context, chunk.data(), count);
    for (unsigned k = 0; k < count; ++k)
      hits[begin + k] = glm::uvec2(chunk[k].hit.geomID, chunk[k].hit.primID);
  });
}

runtime::graph::BufferHandle HostVisibility::add_primary_pass(runtime::graph::RenderGraph& graph,
                                                              const gpu::FrameConstants& frame,
                                                              std::uint32_t width,
                                                              std::uint32_t height) {
  const std::uint64_t pixels = std::max<std::uint64_t>(std::uint64_t{width} * height, 1);
  if (pixels > hit_capacity_) {
    if (hit_capacity_ > 0) device_.wait_idle();  // the old buffers may still be read
    hits_.clear();
    for (std::uint32_t slot = 0; slot < kHitSlots; ++slot) {
      hits_.emplace_back(device_, runtime::BufferDesc{.size = pixels * sizeof(glm::uvec2),
                                                      .usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                                      .memory = runtime::MemoryUsage::Upload,
                                                      .name = "gbuffer.host_hits"});
      if (hits_.back().mapped() == nullptr)
        throw RuntimeError("host visibility: the hit buffer is not mapped");
    }
    hit_capacity_ = pixels;
  }
  // A ring of kHitSlots buffers: this frame's slot was last read by the resolve kHitSlots frames
  // ago, which has finished (at most kHitSlots - 1 frames are in flight). So the import has no
  // prior use to wait for, and the executor runs gbuffer.host at once: the trace overlaps the
  // frame still in flight instead of waiting for it (graph_executor.h).
  // (FrameSession refuses more frames in flight than GpuScene::kStagingSlots - 1.)
  const runtime::Buffer& hits = hits_[hit_slot_];
  hit_slot_ = (hit_slot_ + 1) % kHitSlots;
  auto* records = reinterpret_cast<glm::uvec2*>(hits.mapped());
  const auto record_count = static_cast<std::size_t>(hit_capacity_);
  const runtime::graph::BufferHandle imported = graph.import_buffer(
      "gbuffer.host_hits", hits.handle(), {hits.size()}, {.read_only = false, .initial = {}});
  struct Data {
    runtime::graph::BufferHandle hits;
  };
  return graph
      .add_pass<Data>(
          "gbuffer.host", runtime::graph::PassKind::Host,
          [&](runtime::graph::PassBuilder& b, Data& d) {
            d.hits = b.write(imported, runtime::graph::Access::HostReadWrite);
          },
          [this, records, record_count, frame, width, height](runtime::graph::PassContext&,
                                                               const Data&) {
            trace_primary(frame, width, height, std::span(records, record_count));
          })
      .hits;
}

runtime::graph::BufferHandle HostVisibility::add_shadow_rays(
    runtime::graph::RenderGraph& graph, std::uint32_t slots,
    const std::function<runtime::graph::BufferHandle(runtime::graph::BufferHandle)>& emit) {
  return add_trace_pass(graph, emit(import_rays(graph, slots)), slots);
}

}  // namespace lantern::lighting
