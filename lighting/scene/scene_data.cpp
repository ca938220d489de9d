// Level -> GPU records (scene_data.h): meshes to vertex/index arrays and BLASes, instances to
// GpuInstance + TLAS, materials to GpuMaterial, emitters to the light table.
#include "lighting/scene/scene_data.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <map>
#include <chrono>
#include <cmath>
#include <limits>

#include "engine/core/error.h"
#include "engine/core/log.h"
#include "engine/scene/mesh_tangents.h"
#include "runtime/volume/volume_set.h"
#include "shared/brdf.h"
#include "shared/color.h"
#include "shared/common_math.h"
#include "shared/sampling.h"

namespace lantern::lighting {
namespace {

// `textures`: GpuMaterial.textures from the TextureSet (all kNoTexture without textures).
gpu::GpuMaterial to_gpu_material(const Material& m, glm::uvec4 textures) {
  gpu::GpuMaterial g{};
  g.base_color = m.base_color;
  g.emission = glm::vec4(m.emitted_radiance(), textures.w != gpu::kNoTexture ? m.normal_scale : 0.0f);
  g.params = glm::vec4(m.roughness, m.metallic, m.specular_factor,
                       m.alpha_tested() ? m.alpha_cutoff : 0.0f);
  g.textures = textures;
  return g;
}

// The GpuTexturedEmitter records and texture means of every instance whose emissive material
// has an emissive texture (instance order, triangle order; uvs in the light's winding). Means are
// cached by (texture record contents, the three uvs): instances of one asset, or the repeated
// panels of a generated level, integrate each distinct triangle once.
void build_textured_emitters(const Level& level, SceneData& scene) {
  scene.instance_emitter_record.assign(level.instances.size(), gpu::kNoTexture);
  using Key = std::array<std::uint32_t, 16 + 6>;
  std::map<Key, glm::vec3> cache;
  auto mean_of = [&](std::uint32_t texture, const glm::vec2 (&uv)[3]) {
    Key key{};
    std::memcpy(key.data(), &scene.textures.records()[texture], sizeof(gpu::GpuTexture));
    std::memcpy(key.data() + 16, uv, sizeof(uv));
    auto [it, inserted] = cache.try_emplace(key);
    if (inserted)
      it->second = integrate_texture_over_triangle(scene.textures, texture, uv[0], uv[1], uv[2]);
    return it->second;
  };
  for (std::size_t i = 0; i < level.instances.size(); ++i) {
    const Instance& inst = level.instances[i];
    const Material& material = level.materials.at(inst.material);
    if (!material.emissive() || !material.emissive_texture.present()) continue;
    const std::uint32_t texture = scene.textures.material_textures(inst.material).z;
    const Mesh& mesh = level.meshes.at(inst.mesh);
    const std::vector<glm::vec2>& uvs = mesh.texcoords(material.emissive_texture.texcoord);
    const bool mirrored = glm::determinant(glm::mat3(inst.world)) < 0.0f;
    scene.instance_emitter_record[i] = static_cast<std::uint32_t>(scene.textured_emitters.size());
    for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
      glm::vec2 uv[3];
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t v = mesh.indices[3 * t + static_cast<std::size_t>(k)];
        uv[k] = v < uvs.size() ? uvs[v] : glm::vec2(0.0f);
      }
      if (mirrored) std::swap(uv[1], uv[2]);
      gpu::GpuTexturedEmitter e{};
      e.uv01 = glm::vec4(uv[0], uv[1]);
      e.uv2_tex = glm::vec4(uv[2], glm::uintBitsToFloat(texture), 0.0f);
      scene.textured_emitters.push_back(e);
      scene.textured_emitter_means.push_back(mean_of(texture, uv));
    }
  }
}

// SceneData::vertex_tangents: for each mesh some instance draws with a normal-mapped material,
// its own tangents or generated ones (engine/scene/mesh_tangents.h); zero (w = 0, the shader's
// triangle-frame fallback) for every other vertex. Empty without normal textures.
std::vector<gpu::vec4> vertex_tangents(const Level& level, std::size_t vertex_count) {
  // Per mesh: the texcoord set of the normal texture it is drawn with (the first such instance's),
  // or none.
  constexpr std::uint32_t kNotMapped = ~0u;
  std::vector<std::uint32_t> normal_set(level.meshes.size(), kNotMapped);
  bool any = false;
  for (const Instance& inst : level.instances) {
    if (inst.material >= level.materials.size() || inst.mesh >= level.meshes.size() ||
        !level.materials[inst.material].normal_texture.present())
      continue;
    const std::uint32_t set = level.materials[inst.material].normal_texture.texcoord;
    if (normal_set[inst.mesh] == kNotMapped) {
      normal_set[inst.mesh] = set;
      any = true;
    } else if (normal_set[inst.mesh] != set) {
      // One tangent frame per vertex: the first set wins, and the level is told.
      log::warn("{}: mesh '{}' is normal-mapped through TEXCOORD_{} and TEXCOORD_{}; its "
                "generated tangents follow TEXCOORD_{}",
                level.source.string(), level.meshes[inst.mesh].name, normal_set[inst.mesh], set,
                normal_set[inst.mesh]);
    }
  }
  if (!any) return {};
  std::vector<gpu::vec4> out;
  out.reserve(vertex_count);
  for (std::size_t m = 0; m < level.meshes.size(); ++m) {
    const Mesh& mesh = level.meshes[m];
    if (normal_set[m] == kNotMapped) {
      out.insert(out.end(), mesh.positions.size(), gpu::vec4(0.0f));
    } else if (mesh.tangents.size() == mesh.positions.size()) {
      out.insert(out.end(), mesh.tangents.begin(), mesh.tangents.end());
    } else {
      const std::vector<glm::vec4> generated = generate_tangents(mesh, normal_set[m]);
      out.insert(out.end(), generated.begin(), generated.end());
    }
  }
  return out;
}

// SceneData::vertex_texcoords1: every mesh's TEXCOORD_1 (zero where a mesh has none), when some
// material texture samples set 1; empty otherwise.
std::vector<glm::vec2> vertex_texcoords1(const Level& level, std::size_t vertex_count) {
  bool any = false;
  for (const Material& m : level.materials)
    for (const TextureRef* t : {&m.base_color_texture, &m.metallic_roughness_texture,
                                &m.normal_texture, &m.emissive_texture})
      any = any || (t->present() && t->texcoord == 1);
  if (!any) return {};
  std::vector<glm::vec2> out;
  out.reserve(vertex_count);
  for (const Mesh& mesh : level.meshes) {
    if (mesh.uvs1.size() == mesh.positions.size())
      out.insert(out.end(), mesh.uvs1.begin(), mesh.uvs1.end());
    else
      out.insert(out.end(), mesh.positions.size(), glm::vec2(0.0f));
  }
  return out;
}

}  // namespace

std::uint32_t instance_bvh_flags(const Level& level, const Instance& instance) {
  return instance.material < level.materials.size() &&
                 level.materials[instance.material].alpha_tested()
             ? gpu::kBvhInstanceAlphaTested
             : 0u;
}

float SceneData::scene_radius() const {
  return std::max(0.5f * glm::length(bounds_max - bounds_min), 1e-3f);
}

EmitterTextureRange emitter_texture_range(const SceneData& scene, std::size_t instance) {
  if (instance >= scene.instance_emitter_record.size()) return {};
  return {scene.instance_emitter_record[instance], &scene.textured_emitter_means};
}

void append_triangle_emitters(const Mesh& mesh, const glm::mat4& world, const glm::vec3& radiance,
                              std::uint32_t instance, std::vector<LightEmitter>& out,
                              EmitterTextureRange texture) {
  const bool textured = texture.first_record != gpu::kNoTexture && texture.means != nullptr;
  const float luminance = gpu::luminance(radiance);
  const bool mirrored = glm::determinant(glm::mat3(world)) < 0.0f;
  const std::size_t count = mesh.triangle_count();
  for (std::size_t t = 0; t < count; ++t) {
    glm::vec3 p[3];
    for (int k = 0; k < 3; ++k) {
      const glm::vec3& v = mesh.positions[mesh.indices[3 * t + static_cast<std::size_t>(k)]];
      p[k] = glm::vec3(world * glm::vec4(v, 1.0f));
    }
    if (mirrored) std::swap(p[1], p[2]);
    const float area = gpu::triangle_area(p[0], p[1], p[2]);
    LightEmitter e;
    e.stable_id = (static_cast<std::uint64_t>(instance) << 32) | t;
    e.light.p0 = glm::vec4(p[0], glm::uintBitsToFloat(gpu::kLightTriangle));
    e.light.p1 = glm::vec4(p[1] - p[0], 0.0f);
    e.light.p2 = glm::vec4(p[2] - p[0], 0.0f);
    e.light.radiance = glm::vec4(radiance, 0.0f);
    e.power = gpu::finite_positive_or_zero(luminance * area * gpu::kPi);
    if (textured) {
      const std::uint32_t record = texture.first_record + static_cast<std::uint32_t>(t);
      e.light.radiance.w = glm::uintBitsToFloat(record + 1u);
      const glm::vec3 mean = (*texture.means)[record];
      e.power = gpu::finite_positive_or_zero(gpu::luminance(radiance * mean) * area * gpu::kPi);
    }
    out.push_back(e);
  }
}

LightEmitter analytic_emitter(std::uint32_t index, LightType type, const glm::vec3& position,
                              const glm::vec3& direction, const glm::vec3& intensity,
                              float inner_cone, float outer_cone, float range, float scene_radius) {
  LightEmitter e;
  e.stable_id = kAnalyticLightIdBase | index;
  e.light.radiance = glm::vec4(intensity, 0.0f);
  const float len = glm::length(direction);
  const glm::vec3 dir = len > 0.0f ? direction / len : glm::vec3(0.0f, 0.0f, -1.0f);
  const float luminance = gpu::luminance(intensity);
  switch (type) {
    case LightType::Point:
      e.light.p0 = glm::vec4(position, glm::uintBitsToFloat(gpu::kLightPoint));
      e.light.p2 = glm::vec4(0.0f, 0.0f, 0.0f, std::max(range, 0.0f));
      e.power = 4.0f * gpu::kPi * luminance;
      break;
    case LightType::Spot:
      e.light.p0 = glm::vec4(position, glm::uintBitsToFloat(gpu::kLightSpot));
      e.light.p1 = glm::vec4(dir, 0.0f);
      e.light.p2 =
          glm::vec4(std::cos(outer_cone), std::cos(inner_cone), 0.0f, std::max(range, 0.0f));
      e.power = 4.0f * gpu::kPi * luminance;
      break;
    case LightType::Directional:
      e.light.p0 = glm::vec4(0.0f, 0.0f, 0.0f, glm::uintBitsToFloat(gpu::kLightDirectional));
      e.light.p1 = glm::vec4(dir, 0.0f);
      e.power = luminance * gpu::kPi * scene_radius * scene_radius;
      break;
  }
  e.power = gpu::finite_positive_or_zero(e.power);
  return e;
}

float material_max_gloss(const gpu::GpuMaterial& m) {
  // A metallic-roughness texture scales both factors by at most 1 (gbuffer_material.glsl).
  const float roughness = m.textures.y != gpu::kNoTexture ? 0.0f : m.params.x;
  return gpu::brdf_gloss(roughness, m.params.y, m.params.z);
}

std::vector<LightEmitter> extract_light_emitters(const Level& level, float scene_radius,
                                                 const SceneData* scene) {
  std::vector<LightEmitter> emitters;
  for (std::size_t i = 0; i < level.instances.size(); ++i) {
    const Instance& inst = level.instances[i];
    const Material& material = level.materials.at(inst.material);
    if (!material.emissive()) continue;
    append_triangle_emitters(level.meshes.at(inst.mesh), inst.world, material.emitted_radiance(),
                             static_cast<std::uint32_t>(i), emitters,
                             scene != nullptr ? emitter_texture_range(*scene, i)
                                              : EmitterTextureRange{});
  }
  for (std::size_t k = 0; k < level.lights.size(); ++k) {
    const Light& light = level.lights[k];
    emitters.push_back(analytic_emitter(static_cast<std::uint32_t>(k), light.type, light.position,
                                        light.direction(), light.color * light.intensity,
                                        light.inner_cone, light.outer_cone, light.range,
                                        scene_radius));
  }
  return emitters;
}

std::vector<BvhInstanceDesc> bvh_instance_descs(const Level& level) {
  std::vector<BvhInstanceDesc> descs;
  descs.reserve(level.instances.size());
  for (std::size_t i = 0; i < level.instances.size(); ++i) {
    const Instance& inst = level.instances[i];
    const std::uint32_t flags = instance_bvh_flags(level, inst);
    // Alpha-tested instances stay instanced: the merged tree's record carries no flags.
    const bool fixed = flags == 0 && (!inst.behaviour || !behaviour_moves(*inst.behaviour));
    descs.push_back({inst.mesh, inst.world, static_cast<std::uint32_t>(i), flags, fixed});
  }
  return descs;
}

SceneData build_scene_data(const Level& level) {
  return build_scene_data(level, runtime::load_volume_grids(level));
}

SceneData build_scene_data(const Level& level, const std::vector<runtime::VolumeGrid>& grids) {
  SceneData scene;
  scene.textures = TextureSet::build(level);
  for (std::size_t m = 0; m < level.materials.size(); ++m)
    scene.materials.push_back(
        to_gpu_material(level.materials[m], scene.textures.material_textures(m)));
  if (scene.materials.empty())
    scene.materials.push_back(to_gpu_material(Material{}, glm::uvec4(gpu::kNoTexture)));

  // Meshes: concatenated vertex/index arrays and one BLAS each.
  std::vector<std::uint32_t> first_vertex;
  std::vector<std::uint32_t> first_index;
  for (const Mesh& mesh : level.meshes) {
    first_vertex.push_back(static_cast<std::uint32_t>(scene.vertices.size()));
    first_index.push_back(static_cast<std::uint32_t>(scene.indices.size()));
    for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
      const glm::vec3 n = v < mesh.normals.size() ? mesh.normals[v] : glm::vec3(0.0f);
      const glm::vec2 uv = v < mesh.uvs.size() ? mesh.uvs[v] : glm::vec2(0.0f);
      scene.vertices.push_back({glm::vec4(mesh.positions[v], uv.x), glm::vec4(n, uv.y)});
    }
    scene.indices.insert(scene.indices.end(), mesh.indices.begin(), mesh.indices.end());
    scene.bvh.add_mesh(MeshBvh(mesh.positions, mesh.indices));
  }
  scene.vertex_tangents = vertex_tangents(level, scene.vertices.size());
  scene.vertex_texcoords1 = vertex_texcoords1(level, scene.vertices.size());

  // Participating media: every grid packed into the shared cell and value arrays (none, and
  // OpenVDB untouched, without volumes).
  if (grids.size() != level.volumes.size())
    throw InputError(fmt::format("{}: {} volume grids for {} volumes", level.source.string(),
                                 grids.size(), level.volumes.size()));
  for (std::size_t v = 0; v < grids.size(); ++v) {
    const std::uint32_t first_cell =
        runtime::pack_volume_grid(grids[v], scene.volume_cells, scene.volume_values);
    scene.volumes.push_back(runtime::volume_record(level.volumes[v], grids[v],
                                                   level.volumes[v].transform.matrix(), first_cell));
    scene.volume_grid_to_world.push_back(grids[v].index_to_world);
  }

  // Instances: GpuInstance records, BVH instances and the world box.
  glm::vec3 lo(std::numeric_limits<float>::max());
  glm::vec3 hi(-std::numeric_limits<float>::max());
  for (std::size_t i = 0; i < level.instances.size(); ++i) {
    const Instance& inst = level.instances[i];
    if (inst.mesh >= level.meshes.size() || inst.material >= scene.materials.size()) {
      throw InputError(fmt::format("{}: instance '{}' references mesh {} / material {} of {} / {}",
                                   level.source.string(), inst.name, inst.mesh, inst.material,
                                   level.meshes.size(), scene.materials.size()));
    }
    const Mesh& mesh = level.meshes[inst.mesh];
    gpu::GpuInstance g{};
    g.object_to_world = inst.world;
    g.prev_object_to_world = inst.world;
    g.world_to_object = glm::inverse(inst.world);
    g.geometry =
        glm::uvec4(inst.material, first_index[inst.mesh],
                   static_cast<std::uint32_t>(mesh.indices.size()), first_vertex[inst.mesh]);
    g.bvh = glm::uvec4(0u, gpu::kInvalidLight, glm::floatBitsToUint(1.0f), 0u);  // z: emission scale 1
    scene.instances.push_back(g);
    for (const glm::vec3& p : mesh.positions) {
      const glm::vec3 w = glm::vec3(inst.world * glm::vec4(p, 1.0f));
      lo = glm::min(lo, w);
      hi = glm::max(hi, w);
    }
  }
  scene.bvh.set_instances(bvh_instance_descs(level));
  if (lo.x <= hi.x) {
    scene.bounds_min = lo;
    scene.bounds_max = hi;
  }

  // Lights: the table keeps the order of the emitters, so each instance's first emissive
  // triangle light is found by counting.
  const auto integrate_start = std::chrono::steady_clock::now();
  build_textured_emitters(level, scene);
  scene.textured_emitter_ms = std::chrono::duration<double, std::milli>(
                                  std::chrono::steady_clock::now() - integrate_start)
                                  .count();
  const std::vector<LightEmitter> emitters =
      extract_light_emitters(level, scene.scene_radius(), &scene);
  std::uint32_t light_index = 0;
  for (std::size_t i = 0; i < level.instances.size(); ++i) {
    const Instance& inst = level.instances[i];
    if (!level.materials.empty() && level.materials[inst.material].emissive()) {
      const auto count = static_cast<std::uint32_t>(level.meshes[inst.mesh].triangle_count());
      scene.instances[i].bvh.y = count > 0 ? light_index : gpu::kInvalidLight;
      light_index += count;
      scene.emissive_triangles += count;
    }
  }
  scene.lights.update(emitters, scene.emissive_triangles);
  scene.light_grid = LightGrid(scene.lights.lights(), scene.lights.powers());
  scene.light_spread = measure_light_spread(scene);
  for (const gpu::GpuMaterial& m : scene.materials) {
    scene.max_gloss = std::max(scene.max_gloss, material_max_gloss(m));
  }
  return scene;
}

}  // namespace lantern::lighting
