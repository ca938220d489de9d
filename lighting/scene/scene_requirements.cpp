#include "lighting/scene/scene_requirements.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "lighting/gbuffer/gbuffer_pass.h"
#include "lighting/lights/environment_map.h"
#include "lighting/scene/scene_data.h"
#include "lighting/scene/volume_requirements.h"
#include "lighting/visibility/host_visibility.h"
#include "runtime/volume/volume_set.h"
#include "shared/alias_table.h"
#include "shared/bvh.h"
#include "shared/lights.h"
#include "shared/scene.h"
#include "shared/textures.h"

namespace lantern::lighting {
namespace {

// Bytes of a device array of `count` elements (never-empty: one element at least).
template <class T>
std::uint64_t array_bytes(std::size_t count) {
  return sizeof(T) * std::max<std::uint64_t>(count, 1);
}

std::string mib(std::uint64_t bytes) {
  return fmt::format("{:.2f} MiB", static_cast<double>(bytes) / (1024.0 * 1024.0));
}

}  // namespace

void describe_requirements(const Level& level, std::uint32_t width, std::uint32_t height,
                           LevelSummary& summary, const VisibilityChoice& visibility,
                           GBufferMethod gbuffer_setting) {
  // The volumes' grids are read once, for the scene and for the "volumes" section.
  const std::vector<runtime::VolumeGrid> grids = runtime::load_volume_grids(level);
  const SceneData scene = build_scene_data(level, grids);
  const std::size_t lights = scene.lights.lights().size();
  const std::size_t analytic = lights - scene.emissive_triangles;

  // Light sampling: one power alias table over every emitter, or nothing at all.
  if (lights == 0) {
    summary.enabled["light_sampling"] = {
        {"structure", "none"}, {"why", "the level has no emitters"}, {"bytes", 0}};
  } else {
    const std::uint64_t bytes =
        array_bytes<gpu::GpuLight>(lights) + array_bytes<gpu::AliasEntry>(lights);
    summary.enabled["light_sampling"] = {
        {"structure",
         "power (flux) alias tables, one for the emissive triangles and one for the analytic "
         "lights (a flicker rebuilds only its group's), O(1) per sample"},
        {"why", fmt::format("{} emissive triangles + {} analytic lights", scene.emissive_triangles,
                            analytic)},
        {"emitters", lights},
        {"spread", std::round(double{scene.light_spread.spread} * 100.0) / 100.0},
        {"bytes", bytes},
        {"memory", mib(bytes)}};
    // The light grid (restir.initial's grid candidates; built for every level with a placed
    // light, drawn from where ReSTIR's local lists are on).
    const LightGrid& grid = scene.light_grid;
    const std::uint64_t grid_bytes = array_bytes<std::uint32_t>(grid.gpu_words().size()) +
                                     array_bytes<gpu::uvec2>(grid.light_cells().size());
    const gpu::GpuLightGrid& h = grid.header();
    summary.enabled["light_grid"] = {
        {"structure", "uniform grid of world-space cells over the lights' places, a dense cell "
                      "table and each light's cell record: O(1) draws near a point and densities"},
        {"why", fmt::format("{} placed lights (ReSTIR draws grid_candidates from it where its "
                            "local light lists are on)",
                            h.dims.w)},
        {"cell_edge", std::round(double{h.origin_cell.w} * 1000.0) / 1000.0},
        {"cells", fmt::format("{}x{}x{}, {} occupied", h.dims.x, h.dims.y, h.dims.z,
                              grid.occupied_cells())},
        {"bytes", grid_bytes},
        {"memory", mib(grid_bytes)}};
  }

  // Environment: tables only when the level names a map.
  if (level.environment) {
    const EnvironmentDistribution env = EnvironmentDistribution::load(*level.environment);
    const std::uint64_t bytes = sizeof(gpu::GpuEnvironment) +
                                array_bytes<gpu::vec4>(env.texels().size()) +
                                array_bytes<gpu::AliasEntry>(env.marginal().size()) +
                                array_bytes<gpu::AliasEntry>(env.conditional().size());
    summary.enabled["environment"] = {
        {"structure", "lat-long texels + marginal/conditional alias tables (luminance x solid angle)"},
        {"why", fmt::format("the level names {}", level.environment->path.filename().string())},
        {"resolution", fmt::format("{}x{}", env.width(), env.height())},
        {"bytes", bytes},
        {"memory", mib(bytes)}};
  } else {
    summary.enabled["environment"] = {
        {"structure", "none (a 1-texel black stand-in is bound)"},
        {"why", "the level has no environment map"},
        {"bytes", 0}};
  }

  // Visibility: the scene BVH (compute traversal), and with ray query also a BLAS per mesh and
  // a TLAS over the instances (the driver's; its size is known only on the device).
  const SceneBvh& bvh = scene.bvh;
  const bool host = HostVisibility::answers(visibility.backend, bvh_instance_descs(level));
  std::string traversal = "compute-shader BVH, nodes in texel buffers";
  if (visibility.backend == VisibilityBackend::RayQuery) {
    traversal =
        "VK_KHR_ray_query against a BLAS per mesh and a TLAS rebuilt by scene.tlas_build when "
        "instances move (the BVH stays uploaded)";
  } else if (host) {
    traversal =
        "Embree on the host for the one shadow ray per pixel of restir.shade and "
        "integrators.baseline (visibility.host between two submissions: the fixed instances' "
        "world-space triangles in one scene, the others instanced); the compute-shader BVH for "
        "every other ray";
  } else if (visibility.backend == VisibilityBackend::Host) {
    traversal += " (host visibility declined: alpha-tested materials need the shaders' cutout)";
  }
  const std::uint64_t bvh_bytes = array_bytes<gpu::BvhNode>(bvh.nodes().size()) +
                                  array_bytes<gpu::BvhTriangle>(bvh.triangles().size()) +
                                  array_bytes<gpu::BvhInstance>(bvh.instances().size()) +
                                  sizeof(gpu::BvhSceneHeader);
  summary.enabled["visibility"] = {
      {"structure",
       "SAH BVH: the fixed instances merged into one world-space tree, a BLAS per mesh of the "
       "instances that move, a TLAS over both rebuilt when instances move"},
      {"merged_instances", bvh.merged_instance_count()},
      {"merged_triangles", bvh.merged_triangle_count()},
      {"backend", std::string(visibility_backend_name(visibility.backend))},
      {"backend_why", visibility.why.empty() ? "default" : visibility.why},
      {"traversal", traversal},
      {"nodes", bvh.nodes().size()},
      {"triangles", bvh.triangles().size()},
      {"bytes", bvh_bytes},
      {"memory", mib(bvh_bytes)}};

  const std::uint64_t geometry_bytes = array_bytes<gpu::GpuVertex>(scene.vertices.size()) +
                                       array_bytes<std::uint32_t>(scene.indices.size()) +
                                       array_bytes<gpu::GpuMaterial>(scene.materials.size()) +
                                       array_bytes<gpu::GpuInstance>(scene.instances.size());
  summary.enabled["geometry"] = {{"vertices", scene.vertices.size()},
                                 {"indices", scene.indices.size()},
                                 {"materials", scene.materials.size()},
                                 // The glossiest surface (SceneData::max_gloss): ReSTIR's
                                 // bsdf_min_gloss above it traces no BSDF ray on this level.
                                 {"max_gloss",
                                  std::round(double{scene.max_gloss} * 1000.0) / 1000.0},
                                 {"instances", scene.instances.size()},
                                 {"bytes", geometry_bytes},
                                 {"memory", mib(geometry_bytes)}};

  // Material textures: decoded, mip-mapped texels and one record per material slot, only when a
  // material references an image.
  const TextureSet& textures = scene.textures;
  if (textures.empty()) {
    summary.enabled["textures"] = {
        {"structure", "none (1-element stand-ins are bound; the G-buffer's textured path is "
                      "compiled out)"},
        {"why", "no material references an image"},
        {"bytes", 0}};
  } else {
    nlohmann::json list = nlohmann::json::array();
    for (const TextureImage& img : textures.images()) {
      const ImageRef& ref = level.images[img.image];
      list.push_back(
          {{"image", ref.name.empty() ? (ref.path.empty() ? fmt::format("embedded {}", img.image)
                                                          : ref.path.filename().string())
                                      : ref.name},
           {"size", fmt::format("{}x{}", img.width, img.height)},
           {"mips", img.levels},
           {"encoding", img.format == gpu::kTexelHalf ? "rgba16f linear" : "rgba8 linear"},
           {"bytes", img.bytes}});
    }
    std::size_t alpha_tested = 0;
    for (const Material& m : level.materials) alpha_tested += m.alpha_tested() ? 1 : 0;
    const std::uint64_t bytes = textures.texel_bytes() +
                                array_bytes<gpu::GpuTexture>(textures.records().size()) +
                                array_bytes<gpu::GpuTexturedEmitter>(scene.textured_emitters.size()) +
                                array_bytes<gpu::vec4>(scene.vertex_tangents.size()) +
                                array_bytes<glm::vec2>(scene.vertex_texcoords1.size());
    summary.enabled["textures"] = {
        {"structure", "software-sampled texel array (bilinear, trilinear mips) + records"},
        {"why", fmt::format("{} material texture slots over {} decoded images",
                            textures.records().size(), textures.images().size())},
        {"images", list},
        {"textured_lights", scene.textured_emitters.size()},
        {"alpha_tested", alpha_tested},
        {"vertex_tangents", scene.vertex_tangents.size()},
        {"vertex_texcoords1", scene.vertex_texcoords1.size()},
        {"load_ms", std::round(textures.build_ms() * 10.0) / 10.0},
        {"integrate_ms", std::round(scene.textured_emitter_ms * 10.0) / 10.0},
        {"bytes", bytes},
        {"memory", mib(bytes)}};
  }

  // Per-frame images at this size: the G-buffer of shaders/shared/gbuffer.h (4 rgba32f, 1
  // rgba16f, 1 rgba32ui, D32 depth) and the HDR radiance buffer.
  const std::uint64_t pixels = std::uint64_t{width} * height;
  const std::uint64_t gbuffer = pixels * (5 * 16 + 8 + 4);
  const std::uint64_t hdr = pixels * 16;
  // The G-buffer method the frame uses at this size (GBufferPass::method_for: Auto resolved; its
  // host method only on a CPU device).
  const GBufferMethod gbuffer_method =
      GBufferPass::method_for(gbuffer_setting, GBufferPass::triangle_count(scene.instances), width,
                              height, host && visibility.cpu_device);
  summary.enabled["per_frame"] = {{"size", fmt::format("{}x{}", width, height)},
                                  {"gbuffer_method", gbuffer_method_name(gbuffer_method)},
                                  {"gbuffer_bytes", gbuffer},
                                  {"hdr_bytes", hdr},
                                  {"memory", mib(gbuffer + hdr)},
                                  {"note", "integrator buffers (ReSTIR reservoirs) come on top; "
                                           "`lantern bench --json` reports them"}};

  describe_volumes(level, grids, summary);

  nlohmann::json variants = nlohmann::json::array();
  if (visibility.backend == VisibilityBackend::RayQuery) {
    variants.push_back("visibility: rayquery (LANTERN_VISIBILITY_RAY_QUERY)");
  } else {
    variants.push_back("visibility: bvh (texel nodes)");
  }
  if (host) {
    variants.push_back(
        "visibility: hostemit / hostresolve for the shading passes "
        "(LANTERN_VISIBILITY_HOST_EMIT / _RESOLVE)");
    variants.push_back(
        "visibility: closestemit / closestresolve for restir.initial when it draws BSDF "
        "candidates (LANTERN_VISIBILITY_HOST_CLOSEST_EMIT / _RESOLVE)");
  }
  if (level.environment) variants.push_back("environment sampling: on");
  if (!textures.empty()) variants.push_back("gbuffer: textured (kTextured)");
  if (gbuffer_method == GBufferMethod::Host) {
    variants.push_back("gbuffer: hosthits resolve (LANTERN_GBUFFER_HOST_HITS)");
  }
  summary.enabled["shader_variants"] = variants;
}

}  // namespace lantern::lighting
