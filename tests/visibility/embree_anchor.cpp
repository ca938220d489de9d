#include "tests/visibility/embree_anchor.h"

#include <embree3/rtcore.h>
#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <glm/gtc/type_ptr.hpp>
#include <stdexcept>
#include <thread>

namespace lantern::lighting::test {

std::string_view embree_layout_name(EmbreeLayout layout) {
  return layout == EmbreeLayout::Flat ? "flat" : "two-level";
}

struct EmbreeAnchor::Impl {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  std::vector<RTCScene> mesh_scenes;  // two-level only
  EmbreeLayout layout = EmbreeLayout::Flat;
  unsigned threads = 1;

  ~Impl() {
    if (scene != nullptr) rtcReleaseScene(scene);
    for (RTCScene s : mesh_scenes)
      if (s != nullptr) rtcReleaseScene(s);
    if (device != nullptr) rtcReleaseDevice(device);
  }

  void check(const char* what) const {
    const RTCError error = rtcGetDeviceError(device);
    if (error != RTC_ERROR_NONE)
      throw std::runtime_error(
          fmt::format("embree: {} failed (RTCError {})", what, static_cast<int>(error)));
  }

  // One triangle geometry over `mesh`, its vertices mapped by `to_world` (identity for object
  // space), attached to `target` as geometry `id` (= triangle ids are the mesh's).
  void attach_mesh(RTCScene target, const Mesh& mesh, const glm::mat4& to_world, unsigned id) {
    RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vertices = static_cast<float*>(
        rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                3 * sizeof(float), mesh.positions.size()));
    auto* indices = static_cast<unsigned*>(
        rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                3 * sizeof(unsigned), mesh.triangle_count()));
    check("geometry buffers");
    for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
      const glm::vec3 p = glm::vec3(to_world * glm::vec4(mesh.positions[i], 1.0f));
      vertices[3 * i + 0] = p.x;
      vertices[3 * i + 1] = p.y;
      vertices[3 * i + 2] = p.z;
    }
    for (std::size_t i = 0; i < mesh.triangle_count() * 3; ++i) indices[i] = mesh.indices[i];
    rtcCommitGeometry(geometry);
    rtcAttachGeometryByID(target, geometry, id);
    rtcReleaseGeometry(geometry);
    check("triangle geometry");
  }
};

EmbreeAnchor::EmbreeAnchor(const Level& level, EmbreeLayout layout, unsigned threads)
    : impl_(std::make_unique<Impl>()), layout_(layout) {
  Impl& m = *impl_;
  m.layout = layout;
  m.threads = std::max(1u, threads);
  const std::string config = fmt::format("threads={}", m.threads);
  m.device = rtcNewDevice(config.c_str());
  if (m.device == nullptr) throw std::runtime_error("embree: rtcNewDevice failed");
  const auto v = rtcGetDeviceProperty(m.device, RTC_DEVICE_PROPERTY_VERSION);
  version_ = fmt::format("{}.{}.{}", v / 10000, (v / 100) % 100, v % 100);

  const auto t0 = std::chrono::steady_clock::now();
  m.scene = rtcNewScene(m.device);
  if (layout == EmbreeLayout::Flat) {
    for (std::size_t i = 0; i < level.instances.size(); ++i) {
      const Mesh& mesh = level.meshes.at(level.instances[i].mesh);
      if (mesh.triangle_count() == 0) continue;
      m.attach_mesh(m.scene, mesh, level.instances[i].world, static_cast<unsigned>(i));
    }
  } else {
    m.mesh_scenes.assign(level.meshes.size(), nullptr);
    for (std::size_t k = 0; k < level.meshes.size(); ++k) {
      if (level.meshes[k].triangle_count() == 0) continue;
      m.mesh_scenes[k] = rtcNewScene(m.device);
      m.attach_mesh(m.mesh_scenes[k], level.meshes[k], glm::mat4(1.0f), 0);
      rtcCommitScene(m.mesh_scenes[k]);
      m.check("mesh scene");
    }
    for (std::size_t i = 0; i < level.instances.size(); ++i) {
      RTCScene mesh_scene = m.mesh_scenes.at(level.instances[i].mesh);
      if (mesh_scene == nullptr) continue;
      RTCGeometry instance = rtcNewGeometry(m.device, RTC_GEOMETRY_TYPE_INSTANCE);
      rtcSetGeometryInstancedScene(instance, mesh_scene);
      rtcSetGeometryTransform(instance, 0, RTC_FORMAT_FLOAT4X4_COLUMN_MAJOR,
                              glm::value_ptr(level.instances[i].world));
      rtcCommitGeometry(instance);
      rtcAttachGeometryByID(m.scene, instance, static_cast<unsigned>(i));
      rtcReleaseGeometry(instance);
      m.check("instance geometry");
    }
  }
  rtcCommitScene(m.scene);
  m.check("scene build");
  build_ms_ =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

EmbreeAnchor::~EmbreeAnchor() = default;

std::vector<glm::uvec4> EmbreeAnchor::run(std::span<const gpu::BvhRay> rays, std::uint32_t mode,
                                          double* wall_ms) const {
  const Impl& m = *impl_;
  std::vector<glm::uvec4> out(rays.size(), glm::uvec4(~0u, 0u, 0u, 0u));
  constexpr std::size_t kChunk = 64;
  std::atomic<std::size_t> next{0};
  auto worker = [&] {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    for (std::size_t begin = next.fetch_add(kChunk); begin < rays.size();
         begin = next.fetch_add(kChunk)) {
      const std::size_t end = std::min(rays.size(), begin + kChunk);
      for (std::size_t i = begin; i < end; ++i) {
        const gpu::BvhRay& ray = rays[i];
        const glm::vec3 o(ray.origin), d(ray.direction);
        if (mode == 0) {
          RTCRayHit rh{};
          rh.ray.org_x = o.x, rh.ray.org_y = o.y, rh.ray.org_z = o.z;
          rh.ray.dir_x = d.x, rh.ray.dir_y = d.y, rh.ray.dir_z = d.z;
          rh.ray.tnear = ray.origin.w;
          rh.ray.tfar = ray.direction.w;
          rh.ray.mask = ~0u;
          rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
          rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
          rtcIntersect1(m.scene, &context, &rh);
          if (rh.hit.geomID != RTC_INVALID_GEOMETRY_ID) {
            const unsigned instance =
                m.layout == EmbreeLayout::Flat ? rh.hit.geomID : rh.hit.instID[0];
            out[i] = glm::uvec4(instance, rh.hit.primID, glm::floatBitsToUint(rh.ray.tfar), 0u);
          }
        } else {
          const float t_eps = gpu::bvh_shadow_t_epsilon(o, o + d);
          bool visible = true;
          if (t_eps >= 0.0f) {
            RTCRay r{};
            r.org_x = o.x, r.org_y = o.y, r.org_z = o.z;
            r.dir_x = d.x, r.dir_y = d.y, r.dir_z = d.z;
            r.tnear = t_eps;
            r.tfar = 1.0f - t_eps;
            r.mask = ~0u;
            rtcOccluded1(m.scene, &context, &r);
            visible = r.tfar >= 0.0f;  // Embree sets tfar to -inf on a hit
          }
          out[i].w = visible ? 1u : 0u;
        }
      }
    }
  };
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < m.threads; ++t) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();
  if (wall_ms != nullptr)
    *wall_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

double probe_agreement(std::span<const glm::uvec4> a, std::span<const glm::uvec4> b,
                       std::uint32_t mode) {
  if (a.size() != b.size()) return 0.0;
  if (a.empty()) return 1.0;
  std::size_t same = 0;
  for (std::size_t i = 0; i < a.size(); ++i)
    same += mode == 0 ? ((a[i].x == ~0u) == (b[i].x == ~0u)) : (a[i].w == b[i].w);
  return static_cast<double>(same) / static_cast<double>(a.size());
}

}  // namespace lantern::lighting::test
