// scene.upload: device buffers of the scene and their per-frame update (gpu_scene.h).
#include "lighting/scene/gpu_scene.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <numeric>
#include <string>

#include "engine/core/error.h"
#include "engine/core/log.h"
#include "lighting/visibility/host_visibility.h"
#include "lighting/visibility/ray_query_scene.h"
#include "runtime/core/device.h"
#include "runtime/gpu/transfer.h"

namespace lantern::lighting {
namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// How an imported scene buffer may have been used by the previous frames (conservative: any
// stage, any access), so the first use this frame is ordered after all of them.
constexpr runtime::graph::AccessState kAnyPriorUse{
    VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
    VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT, VK_IMAGE_LAYOUT_UNDEFINED};

std::uint32_t float_bits(float f) {
  std::uint32_t u = 0;
  std::memcpy(&u, &f, sizeof(u));
  return u;
}

}  // namespace

GpuScene::GpuScene(runtime::Device& device, std::shared_ptr<const Level> level,
                   VisibilityBackend visibility)
    : device_(device), level_(std::move(level)) {
  if (!level_) throw InputError("GpuScene: no level");
  if (visibility == VisibilityBackend::RayQuery && !device_.caps().ray_query) {
    throw InputError(
        fmt::format("ray-query visibility needs VK_KHR_ray_query, which device '{}' lacks; use bvh",
                    device_.info().name));
  }
  data_ = build_scene_data(*level_);
  scene_radius_ = data_.scene_radius();
  for (gpu::GpuInstance& g : data_.instances) g.bvh.z = float_bits(1.0f);

  // Emitters in the order build_scene_data put them in the light table: emissive instances'
  // triangles in instance order, then analytic lights.
  emitters_ = extract_light_emitters(*level_, scene_radius_, &data_);
  std::uint32_t first = 0;
  for (std::size_t i = 0; i < level_->instances.size(); ++i) {
    const Instance& inst = level_->instances[i];
    const Material& material = level_->materials.at(inst.material);
    if (!material.emissive()) continue;
    EmissiveInstance e;
    e.instance = static_cast<std::uint32_t>(i);
    e.first = first;
    e.count = static_cast<std::uint32_t>(level_->meshes.at(inst.mesh).triangle_count());
    e.world = inst.world;
    e.radiance = material.emitted_radiance();
    first += e.count;
    emissive_.push_back(e);
  }
  triangle_emitters_ = first;
  // The shaders split the light draw's two groups at frame.counts.z (emissive_triangles): the
  // light table's first group must end there too.
  if (triangle_emitters_ != data_.emissive_triangles ||
      data_.lights.first_group_size() != data_.emissive_triangles) {
    throw RuntimeError(fmt::format(
        "scene '{}': {} emissive triangles in the light list but {} in the scene data ({} in the "
        "light table's first group)",
        level_->name, triangle_emitters_, data_.emissive_triangles,
        data_.lights.first_group_size()));
  }
  bvh_descs_ = bvh_instance_descs(*level_);
  remap_.resize(data_.lights.lights().size());
  for (std::uint32_t i = 0; i < remap_.size(); ++i) remap_[i] = i;
  constants_.environment = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);

  // Environment: the level's map once, or the black stand-in (one texel, one alias entry).
  if (level_->environment) {
    env_.emplace(EnvironmentDistribution::load(*level_->environment));
    env_header_ = env_->header();
    env_power_ = env_->power_estimate(scene_radius_);
  } else {
    env_header_.world_to_map = glm::mat4(1.0f);
    env_header_.map_to_world = glm::mat4(1.0f);
    env_header_.size = glm::uvec4(1u, 1u, 0u, 0u);
    env_header_.params = glm::vec4(0.0f);
    env_dummy_texels_.assign(1, gpu::vec4(0.0f));
    env_dummy_alias_.assign(1, gpu::AliasEntry{1.0f, 0u, 1.0f, 0u});
  }
  update_environment_probability();
  if (env_) {
    log::debug(
        "scene: environment {}x{} ({}), mean luminance {:.4g}, selected by {:.3f} of light "
        "samples",
        env_->width(), env_->height(), level_->environment->path.string(), env_->mean_luminance(),
        env_header_.params.x);
  }

  // What the rows upload from: members whose addresses never change (the environment's arrays are
  // fixed once loaded; the other contents change in place).
  sources_.frame_constants = &constants_;
  sources_.data = &data_;
  sources_.light_previous_to_current = &remap_;
  sources_.env_header = &env_header_;
  sources_.env_texels = env_ ? std::as_bytes(std::span(env_->texels()))
                             : std::as_bytes(std::span(env_dummy_texels_));
  sources_.env_marginal = env_ ? std::as_bytes(std::span(env_->marginal()))
                               : std::as_bytes(std::span(env_dummy_alias_));
  sources_.env_conditional = env_ ? std::as_bytes(std::span(env_->conditional()))
                                  : std::as_bytes(std::span(env_dummy_alias_));
  for (std::uint32_t s = 0; s < gpu::kSceneBufferCount; ++s) {
    if (kSceneBuffers[s].kind != SceneResourceKind::Buffer) continue;
    ensure_capacity(s);
    // Everything starts uploaded (blocking, setup time); per-frame changes go through the graph.
    std::vector<std::byte> bytes(arrays_[s].buffer.size());  // zero-filled past the array
    const std::span<const std::byte> src = cpu_bytes(s);
    std::copy(src.begin(), src.end(), bytes.begin());
    runtime::upload_buffer(device_, arrays_[s].buffer, std::span<const std::byte>(bytes));
    arrays_[s].dirty.clear();
  }
  // BLASes and the TLAS of the level's placement (blocking, setup time).
  if (visibility == VisibilityBackend::RayQuery)
    ray_query_ = std::make_unique<RayQueryScene>(device_, data_.bvh);
  // Embree's scene for the host backend (setup time); levels it cannot answer keep the BVH.
  if (visibility == VisibilityBackend::Host) {
    if (HostVisibility::answers(visibility, bvh_descs_)) {
      host_ = std::make_unique<HostVisibility>(device_, data_.bvh, bvh_descs_);
      log::debug("scene: host visibility ({}, {} threads), {} instances merged, built in {:.1f} ms",
                 host_->version(), host_->threads(), host_->merged_instances(),
                 host_->build_ms());
    } else {
      log::info(
          "visibility=host: level '{}' has alpha-tested materials, whose cutout only the shaders "
          "evaluate; its shadow rays stay on the compute BVH",
          level_->name);
    }
  }
}

GpuScene::~GpuScene() = default;

std::span<const std::byte> GpuScene::cpu_bytes(std::uint32_t slot) const {
  if (kSceneBuffers[slot].bytes == nullptr) return {};  // built on the device (the TLAS)
  return kSceneBuffers[slot].bytes(sources_);
}

void GpuScene::mark_dirty(std::uint32_t slot, std::uint64_t begin, std::uint64_t end) {
  if (begin < end) arrays_[slot].dirty.emplace_back(begin, end);
}

void GpuScene::mark_all_dirty(std::uint32_t slot) {
  mark_dirty(slot, 0, cpu_bytes(slot).size());
}

void GpuScene::ensure_capacity(std::uint32_t slot) {
  if (kSceneBuffers[slot].kind != SceneResourceKind::Buffer) return;
  DeviceArray& a = arrays_[slot];
  // Never empty: Vulkan has no zero-sized buffers (an empty array reads as one zeroed element).
  const VkDeviceSize needed = std::max<VkDeviceSize>(cpu_bytes(slot).size(), 16);
  if (a.buffer && a.buffer.size() >= needed) return;
  VkDeviceSize size = needed;
  if (a.buffer) {
    size = std::max<VkDeviceSize>(needed, a.buffer.size() + a.buffer.size() / 2);
    retired_.push_back({uploads_, std::move(a.buffer), std::move(a.texels)});
  }
  const char* texel_name = kSceneBuffers[slot].texel_name;
  a.buffer = runtime::Buffer(
      device_,
      {.size = size,
       .usage = texel_name != nullptr ? VkBufferUsageFlags{VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
                                                           VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT}
                                      : VkBufferUsageFlags{VK_BUFFER_USAGE_STORAGE_BUFFER_BIT},
       .memory = runtime::MemoryUsage::DeviceLocal,
       .name = kSceneBuffers[slot].graph_name});
  if (texel_name != nullptr) {
    a.texels = runtime::BufferView(device_, a.buffer, VK_FORMAT_R32G32B32A32_UINT,
                                   fmt::format("{}.texels", kSceneBuffers[slot].graph_name));
  }
  // A fresh buffer holds nothing: the next scene.upload copies the whole array.
  mark_all_dirty(slot);
}

void GpuScene::update(const FrameSnapshot& snapshot) {
  const auto start = Clock::now();
  stats_ = {};
  update_instances(snapshot);
  stats_.instance_ms = ms_since(start);
  const auto lights_start = Clock::now();
  update_lights(snapshot);
  stats_.light_ms = ms_since(lights_start);
  update_volumes(snapshot);
  stats_.cpu_ms = ms_since(start);
}

void GpuScene::update_instances(const FrameSnapshot& snapshot) {
  const std::size_t count = data_.instances.size();
  bool moved = false;
  std::uint64_t lo = ~0ull;
  std::uint64_t hi = 0;
  for (const SnapshotInstance& s : snapshot.instances) {
    if (s.stable_id >= count || s.mesh != level_->instances[s.stable_id].mesh) {
      throw InputError(fmt::format(
          "frame {}: snapshot instance {} (mesh {}) is not an instance of level '{}' ({} "
          "instances)",
          snapshot.frame_index, s.stable_id, s.mesh, level_->name, count));
    }
    if (s.material >= data_.materials.size()) {
      throw InputError(fmt::format("frame {}: snapshot instance {} uses material {} of {}",
                                   snapshot.frame_index, s.stable_id, s.material,
                                   data_.materials.size()));
    }
    gpu::GpuInstance& g = data_.instances[s.stable_id];
    bool changed = false;
    if (g.object_to_world != s.object_to_world) {
      g.object_to_world = s.object_to_world;
      g.world_to_object = glm::inverse(s.object_to_world);
      bvh_descs_[s.stable_id].object_to_world = s.object_to_world;
      moved = true;
      ++stats_.moved_instances;
      changed = true;
    }
    if (g.prev_object_to_world != s.prev_object_to_world) {
      g.prev_object_to_world = s.prev_object_to_world;
      changed = true;
    }
    const std::uint32_t scale = float_bits(s.emission_scale);
    if (g.geometry.x != s.material || g.bvh.z != scale) {
      g.geometry.x = s.material;
      g.bvh.z = scale;
      changed = true;
    }
    if (changed) {
      lo = std::min<std::uint64_t>(lo, s.stable_id);
      hi = std::max<std::uint64_t>(hi, s.stable_id + 1);
    }
  }
  if (lo < hi) {
    mark_dirty(gpu::kSceneInstances, lo * sizeof(gpu::GpuInstance), hi * sizeof(gpu::GpuInstance));
  }
  if (moved) {
    const std::uint64_t blas_generation = data_.bvh.blas_generation();
    data_.bvh.set_instances(bvh_descs_);
    if (host_) host_->update(bvh_descs_);
    stats_.tlas_rebuilt = true;
    tlas_dirty_ = ray_query_ != nullptr;
    ensure_capacity(gpu::kSceneBvhNodes);
    if (data_.bvh.blas_generation() != blas_generation) {
      // A fixed instance moved: the merged tree and the packed BLASes changed, not only the TLAS.
      ensure_capacity(gpu::kSceneBvhTriangles);
      mark_all_dirty(gpu::kSceneBvhTriangles);
      mark_all_dirty(gpu::kSceneBvhNodes);
    }
    const gpu::BvhSceneHeader& h = data_.bvh.header();
    mark_dirty(gpu::kSceneBvhNodes, std::uint64_t{h.tlas_node_offset} * sizeof(gpu::BvhNode),
               data_.bvh.nodes().size() * sizeof(gpu::BvhNode));
    mark_all_dirty(gpu::kSceneBvhHeader);
    ensure_capacity(gpu::kSceneBvhInstances);
    mark_all_dirty(gpu::kSceneBvhInstances);
  }
}

// A volume's record follows its placement this frame: the grid's own index-to-world, then the
// snapshot's object_to_world (behaviours move volumes like instances), and carries its motion
// since last frame from the snapshot's prev_object_to_world (identity when still, and in a
// frozen snapshot), which the media reservoirs' reuse follows.
void GpuScene::update_volumes(const FrameSnapshot& snapshot) {
  for (const SnapshotVolume& s : snapshot.volumes) {
    if (s.stable_id >= data_.volumes.size()) {
      throw InputError(fmt::format("frame {}: snapshot volume {} is not a volume of level '{}' ({} "
                                   "volumes)",
                                   snapshot.frame_index, s.stable_id, level_->name,
                                   data_.volumes.size()));
    }
    gpu::GpuVolume& v = data_.volumes[s.stable_id];
    const glm::mat4 index_to_world = s.object_to_world * data_.volume_grid_to_world[s.stable_id];
    const bool still = s.prev_object_to_world == s.object_to_world;
    const glm::mat4 motion =
        still ? glm::mat4(1.0f) : s.object_to_world * glm::inverse(s.prev_object_to_world);
    if (v.index_to_world == index_to_world && v.motion == motion) continue;
    v.index_to_world = index_to_world;
    v.world_to_index = glm::inverse(index_to_world);
    v.motion = motion;
    v.motion_inverse =
        still ? glm::mat4(1.0f) : s.prev_object_to_world * glm::inverse(s.object_to_world);
    mark_dirty(gpu::kSceneVolumes, std::uint64_t{s.stable_id} * sizeof(gpu::GpuVolume),
               std::uint64_t{s.stable_id + 1} * sizeof(gpu::GpuVolume));
  }
}

void GpuScene::update_lights(const FrameSnapshot& snapshot) {
  bool changed = false;
  // What changed in place (same lights, same order): the light table re-reads only these.
  std::vector<LightRange> changed_ranges;
  bool same_lights = true;
  // Emissive triangles: re-extract the instances that moved or changed emission scale.
  std::vector<LightEmitter> scratch;
  for (EmissiveInstance& e : emissive_) {
    const gpu::GpuInstance& g = data_.instances[e.instance];
    float scale = 0.0f;
    std::memcpy(&scale, &g.bvh.z, sizeof(scale));
    if (g.object_to_world == e.world && scale == e.scale) continue;
    e.world = g.object_to_world;
    e.scale = scale;
    scratch.clear();
    const Mesh& mesh = level_->meshes[level_->instances[e.instance].mesh];
    append_triangle_emitters(mesh, e.world, e.radiance * std::max(scale, 0.0f), e.instance,
                             scratch, emitter_texture_range(data_, e.instance));
    std::copy(scratch.begin(), scratch.end(), emitters_.begin() + e.first);
    mark_dirty(gpu::kSceneLights, std::uint64_t{e.first} * sizeof(gpu::GpuLight),
               std::uint64_t{e.first + e.count} * sizeof(gpu::GpuLight));
    ++stats_.reextracted_instances;
    stats_.reextracted_triangles += e.count;
    changed_ranges.push_back({e.first, e.count});
    changed = true;
  }
  // Analytic lights: the snapshot's, in stable-id order.
  std::vector<LightEmitter> analytic;
  analytic.reserve(snapshot.lights.size());
  for (const SnapshotLight& l : snapshot.lights) {
    analytic.push_back(analytic_emitter(l.stable_id, static_cast<LightType>(l.type), l.position,
                                        l.direction, l.color * l.intensity, l.inner_cone,
                                        l.outer_cone, l.range, scene_radius_));
  }
  const std::size_t old_analytic = emitters_.size() - triangle_emitters_;
  const auto first_analytic = emitters_.begin() + triangle_emitters_;
  const bool same_ids = analytic.size() == old_analytic &&
                        std::equal(analytic.begin(), analytic.end(), first_analytic,
                                   [](const LightEmitter& a, const LightEmitter& b) {
                                     return a.stable_id == b.stable_id;
                                   });
  if (!same_ids || !std::equal(analytic.begin(), analytic.end(), first_analytic,
                               [](const LightEmitter& a, const LightEmitter& b) {
                                 return a.power == b.power &&
                                        std::memcmp(&a.light, &b.light, sizeof(a.light)) == 0;
                               })) {
    same_lights = same_ids;
    emitters_.resize(triangle_emitters_);
    emitters_.insert(emitters_.end(), analytic.begin(), analytic.end());
    changed_ranges.push_back({triangle_emitters_, analytic.size()});
    mark_dirty(gpu::kSceneLights, std::uint64_t{triangle_emitters_} * sizeof(gpu::GpuLight),
               emitters_.size() * sizeof(gpu::GpuLight));
    changed = true;
  }

  if (changed) {
    stats_.lights_changed = true;
    // Lights that only moved or changed power keep their indices: the table re-reads just them.
    stats_.alias_rebuilt = same_lights ? data_.lights.update_ranges(emitters_, changed_ranges)
                                       : data_.lights.update(emitters_, triangle_emitters_);
    ensure_capacity(gpu::kSceneLights);  // ranges marked above (everything when the buffer grew)
    if (stats_.alias_rebuilt) {
      // Only the rebuilt groups' entries (the flickering analytic lights', not the triangles').
      const LightRange r = data_.lights.alias_rewritten();
      mark_dirty(gpu::kSceneLightAlias, std::uint64_t{r.first} * sizeof(gpu::AliasEntry),
                 std::uint64_t{r.first + r.count} * sizeof(gpu::AliasEntry));
      ensure_capacity(gpu::kSceneLightAlias);
    }
  }
  // The previous -> current index map; uploaded only when it differs from last frame's.
  auto set_remap = [&](std::vector<std::uint32_t>&& next) {
    if (next == remap_) return;
    remap_ = std::move(next);
    ensure_capacity(gpu::kSceneLightPreviousToCurrent);
    mark_all_dirty(gpu::kSceneLightPreviousToCurrent);
  };
  if (changed && !same_lights) {
    set_remap(std::vector<std::uint32_t>(data_.lights.previous_to_current()));
    remap_is_identity_ = false;
    // Lights came or went, so indices moved: the grid is binned again (lights that only move
    // keep the cells they were binned in, which the grid's densities agree with).
    data_.light_grid = LightGrid(data_.lights.lights(), data_.lights.powers());
    for (std::uint32_t slot : {gpu::kSceneLightGrid, gpu::kSceneLightCells}) {
      ensure_capacity(slot);
      mark_all_dirty(slot);
    }
  } else if (!remap_is_identity_ || remap_.size() != data_.lights.lights().size()) {
    // Every light keeps its index (O(lights) once, not every frame).
    std::vector<std::uint32_t> identity(data_.lights.lights().size());
    std::iota(identity.begin(), identity.end(), 0u);
    set_remap(std::move(identity));
    remap_is_identity_ = true;
  }
  if (changed) update_environment_probability();
}

void GpuScene::update_environment_probability() {
  if (!env_) return;  // the stand-in is never selected (params.x stays 0)
  const double lights_power = data_.lights.total_power();
  const float p = environment_selection_probability(env_power_, lights_power);
  if (p == env_header_.params.x) return;
  env_header_.params.x = p;
  mark_all_dirty(gpu::kSceneEnvHeader);
}

void GpuScene::set_frame_constants(const gpu::FrameConstants& constants) {
  constants_ = constants;
  mark_all_dirty(gpu::kSceneFrameConstants);
}

SceneHandles GpuScene::import(runtime::graph::RenderGraph& graph) const {
  SceneHandles h;
  for (const SceneBufferRow& row : kSceneBuffers) {
    if (row.kind == SceneResourceKind::AccelerationStructure) {
      if (!ray_query_) continue;  // BVH scene: no TLAS (a rayquery pipeline is refused)
      const runtime::Buffer& storage = ray_query_->tlas_structure().storage();
      h[row.slot] = graph.import_buffer(row.graph_name, storage.handle(), {storage.size()},
                                        {.read_only = false, .initial = kAnyPriorUse});
      h.tlas = ray_query_->tlas();
      continue;
    }
    const DeviceArray& a = arrays_[row.slot];
    h[row.slot] = graph.import_buffer(row.graph_name, a.buffer.handle(), {a.buffer.size()},
                                      {.read_only = row.read_only, .initial = kAnyPriorUse});
    h.texel_views[row.slot] = a.texels ? a.texels.handle() : VK_NULL_HANDLE;
  }
  return h;
}

SceneHandles GpuScene::add_upload_pass(runtime::graph::RenderGraph& graph,
                                       const SceneHandles& imported) {
  // Release buffers retired long enough ago that no frame in flight can still read them.
  while (!retired_.empty() && uploads_ >= retired_.front().upload + kRetireFrames) {
    retired_.pop_front();
  }

  // Merge each buffer's dirty ranges (sorted, gaps under 4 KiB joined, clamped to the array).
  std::vector<Copy> copies;
  std::uint64_t total = 0;
  for (std::uint32_t s = 0; s < gpu::kSceneBufferCount; ++s) {
    DeviceArray& a = arrays_[s];
    if (a.dirty.empty()) continue;
    const std::uint64_t size = cpu_bytes(s).size();
    std::sort(a.dirty.begin(), a.dirty.end());
    Copy copy{s, {}};
    for (auto [begin, end] : a.dirty) {
      end = std::min(end, size);
      if (begin >= end) continue;
      if (!copy.regions.empty() &&
          begin <= copy.regions.back().dstOffset + copy.regions.back().size + 4096) {
        VkBufferCopy& last = copy.regions.back();
        last.size = std::max(last.dstOffset + last.size, end) - last.dstOffset;
      } else {
        copy.regions.push_back(VkBufferCopy{0, begin, end - begin});
      }
    }
    a.dirty.clear();
    for (const VkBufferCopy& r : copy.regions) total += (r.size + 15) / 16 * 16;
    if (!copy.regions.empty()) copies.push_back(std::move(copy));
  }

  // Stage them into the ring slot no frame in flight uses.
  const std::uint32_t ring_slot = static_cast<std::uint32_t>(uploads_ % kStagingSlots);
  runtime::Buffer& staging = staging_[ring_slot];
  if (total > 0 && (!staging || staging.size() < total)) {
    staging = runtime::Buffer(device_, {.size = std::max<VkDeviceSize>(total + total / 4, 4096),
                                        .usage = 0,
                                        .memory = runtime::MemoryUsage::Upload,
                                        .name = fmt::format("scene.staging.{}", ring_slot)});
  }
  std::uint64_t offset = 0;
  for (Copy& c : copies) {
    const std::span<const std::byte> src = cpu_bytes(c.slot);
    for (VkBufferCopy& r : c.regions) {
      std::memcpy(staging.mapped() + offset, src.data() + r.dstOffset, r.size);
      r.srcOffset = offset;
      offset += (r.size + 15) / 16 * 16;
    }
  }
  stats_.upload_bytes = offset;
  ++uploads_;

  SceneHandles out = imported;
  if (!copies.empty()) add_copy_pass(graph, staging, copies, out);
  if (tlas_dirty_) add_tlas_build_pass(graph, ring_slot, out);
  return out;
}

void GpuScene::add_copy_pass(runtime::graph::RenderGraph& graph, const runtime::Buffer& staging,
                             const std::vector<Copy>& copies, SceneHandles& out) {
  const runtime::graph::BufferHandle source =
      graph.import_buffer("scene.staging", staging.handle(), {staging.size()},
                          {.read_only = true,
                           .initial = {VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_WRITE_BIT,
                                       VK_IMAGE_LAYOUT_UNDEFINED}});
  struct Data {
    runtime::graph::BufferHandle source;
    std::vector<std::pair<runtime::graph::BufferHandle, std::vector<VkBufferCopy>>> copies;
  };
  graph.add_pass<Data>(
      "scene.upload", runtime::graph::PassKind::Transfer,
      [&](runtime::graph::PassBuilder& b, Data& d) {
        d.source = source;
        b.read(source, runtime::graph::Access::TransferSrc);
        for (const Copy& c : copies) {
          runtime::graph::BufferHandle& h = out[c.slot];  // one copy per buffer
          h = b.write(h, runtime::graph::Access::TransferDst);
          d.copies.emplace_back(h, c.regions);
        }
      },
      [](runtime::graph::PassContext& ctx, const Data& d) {
        const VkBuffer src = ctx.buffer(d.source);
        for (const auto& [h, regions] : d.copies) {
          vkCmdCopyBuffer(ctx.cmd(), src, ctx.buffer(h), static_cast<std::uint32_t>(regions.size()),
                          regions.data());
        }
      });
}

void GpuScene::add_tlas_build_pass(runtime::graph::RenderGraph& graph, std::uint32_t ring_slot,
                                   SceneHandles& out) {
  static_assert(kStagingSlots == RayQueryScene::kInstanceSlots);
  tlas_dirty_ = false;
  // The records of this upload's ring slot, which no frame in flight reads (kStagingSlots ==
  // RayQueryScene::kInstanceSlots).
  ray_query_->write_instances(data_.bvh, ring_slot);
  const runtime::Buffer& records = ray_query_->instance_records(ring_slot);
  const runtime::Buffer& scratch = ray_query_->scratch().buffer();
  const runtime::graph::BufferHandle records_h =
      graph.import_buffer("scene.tlas_instances", records.handle(), {records.size()},
                          {.read_only = true,
                           .initial = {VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_WRITE_BIT,
                                       VK_IMAGE_LAYOUT_UNDEFINED}});
  const runtime::graph::BufferHandle scratch_h =
      graph.import_buffer("scene.tlas_scratch", scratch.handle(), {scratch.size()},
                          {.read_only = false, .initial = kAnyPriorUse});
  struct Data {
    runtime::graph::BufferHandle scratch;
    runtime::graph::BufferHandle tlas;
  };
  graph.add_pass<Data>(
      "scene.tlas_build", runtime::graph::PassKind::Compute,
      [&](runtime::graph::PassBuilder& b, Data& d) {
        using runtime::graph::Access;
        b.read(records_h, Access::AccelerationStructureBuildInput);
        d.scratch = b.write(scratch_h, Access::AccelerationStructureBuild);
        runtime::graph::BufferHandle& tlas = out[gpu::kSceneTlas];
        tlas = b.write(tlas, Access::AccelerationStructureBuild);
        d.tlas = tlas;
      },
      [scene = ray_query_.get(), ring_slot](runtime::graph::PassContext& ctx, const Data&) {
        scene->record_tlas_build(ctx.cmd(), ring_slot);
      });
}

std::uint32_t GpuScene::light_count() const {
  return data_.lights.has_power() ? static_cast<std::uint32_t>(data_.lights.lights().size()) : 0u;
}

std::uint64_t GpuScene::bytes() const {
  std::uint64_t total = 0;
  for (const DeviceArray& a : arrays_) total += a.buffer.size();
  return total;
}

}  // namespace lantern::lighting
