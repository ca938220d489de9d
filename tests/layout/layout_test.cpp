// Every shared GPU/CPU struct has the same layout in C++ and in GLSL std430: C++ offsetof/sizeof
// against the Offset/ArrayStride decorations glslang wrote into layout_probe.comp.spv. A scan of
// shaders/shared/*.h makes sure a new struct cannot be added without being checked here.
#include <gtest/gtest.h>

#include <cstddef>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "shared/alias_table.h"
#include "shared/bvh.h"
#include "shared/denoise.h"
#include "shared/environment.h"
#include "shared/host_visibility.h"
#include "shared/light_grid.h"
#include "shared/lights.h"
#include "shared/reservoir.h"
#include "shared/reservoir_pack.h"
#include "shared/restir.h"
#include "shared/scene.h"
#include "shared/upscale.h"
#include "shared/textures.h"
#include "shared/volume.h"
#include "shared/volume_grid.h"
#include "shared/volume_restir.h"
#include "runtime/gpu/shader_library.h"
#include "runtime/gpu/spirv_reflect.h"

namespace lantern::test {
namespace {

struct MemberLayout {
  const char* name;
  std::size_t offset;
};

struct StructLayout {
  const char* name;
  std::size_t size;
  std::vector<MemberLayout> members;  // in declaration order
};

#define LANTERN_MEMBER(type, member)     \
  MemberLayout {                         \
#member, offsetof(gpu::type, member) \
  }

// One row per shared struct. Add new structs here (and a buffer of them in layout_probe.comp).
const std::vector<StructLayout>& cpp_layouts() {
  static const std::vector<StructLayout> table = {
      {"AliasEntry",
       sizeof(gpu::AliasEntry),
       {LANTERN_MEMBER(AliasEntry, threshold), LANTERN_MEMBER(AliasEntry, alias),
        LANTERN_MEMBER(AliasEntry, pdf), LANTERN_MEMBER(AliasEntry, pad0)}},
      {"GpuEnvironment",
       sizeof(gpu::GpuEnvironment),
       {LANTERN_MEMBER(GpuEnvironment, world_to_map), LANTERN_MEMBER(GpuEnvironment, map_to_world),
        LANTERN_MEMBER(GpuEnvironment, size), LANTERN_MEMBER(GpuEnvironment, params)}},
      {"GpuLight",
       sizeof(gpu::GpuLight),
       {LANTERN_MEMBER(GpuLight, p0), LANTERN_MEMBER(GpuLight, p1), LANTERN_MEMBER(GpuLight, p2),
        LANTERN_MEMBER(GpuLight, radiance)}},
      {"LightSample",
       sizeof(gpu::LightSample),
       {LANTERN_MEMBER(LightSample, light_index), LANTERN_MEMBER(LightSample, u),
        LANTERN_MEMBER(LightSample, v), LANTERN_MEMBER(LightSample, target_pdf)}},
      {"Reservoir",
       sizeof(gpu::Reservoir),
       {LANTERN_MEMBER(Reservoir, selected), LANTERN_MEMBER(Reservoir, weight_sum),
        LANTERN_MEMBER(Reservoir, M), LANTERN_MEMBER(Reservoir, W),
        LANTERN_MEMBER(Reservoir, age)}},
      {"PackedReservoir",
       sizeof(gpu::PackedReservoir),
       {LANTERN_MEMBER(PackedReservoir, light_age), LANTERN_MEMBER(PackedReservoir, uv),
        LANTERN_MEMBER(PackedReservoir, W), LANTERN_MEMBER(PackedReservoir, m_target)}},
      {"RestirPush",
       sizeof(gpu::RestirPush),
       {LANTERN_MEMBER(RestirPush, tile_stride), LANTERN_MEMBER(RestirPush, flags),
        LANTERN_MEMBER(RestirPush, light_candidates), LANTERN_MEMBER(RestirPush, bsdf_candidates),
        LANTERN_MEMBER(RestirPush, bias_correction), LANTERN_MEMBER(RestirPush, debug_view),
        LANTERN_MEMBER(RestirPush, neighbours), LANTERN_MEMBER(RestirPush, spatial_pass),
        LANTERN_MEMBER(RestirPush, boost_neighbours), LANTERN_MEMBER(RestirPush, short_history_m),
        LANTERN_MEMBER(RestirPush, radius), LANTERN_MEMBER(RestirPush, m_cap),
        LANTERN_MEMBER(RestirPush, boiling_filter),
        LANTERN_MEMBER(RestirPush, presample_tiles),
        LANTERN_MEMBER(RestirPush, visibility_reuse), LANTERN_MEMBER(RestirPush, tile_bands),
        LANTERN_MEMBER(RestirPush, similarity), LANTERN_MEMBER(RestirPush, local_candidates),
        LANTERN_MEMBER(RestirPush, permutation_bits), LANTERN_MEMBER(RestirPush, m_cap_moving),
        LANTERN_MEMBER(RestirPush, bsdf_min_gloss),
        LANTERN_MEMBER(RestirPush, temporal_neighbours),
        LANTERN_MEMBER(RestirPush, reservoir_stride), LANTERN_MEMBER(RestirPush, representative),
        LANTERN_MEMBER(RestirPush, grid_candidates)}},
      {"GpuLightGrid",
       sizeof(gpu::GpuLightGrid),
       {LANTERN_MEMBER(GpuLightGrid, origin_cell), LANTERN_MEMBER(GpuLightGrid, dims)}},
      {"GpuLightGridCell",
       sizeof(gpu::GpuLightGridCell),
       {LANTERN_MEMBER(GpuLightGridCell, first), LANTERN_MEMBER(GpuLightGridCell, count),
        LANTERN_MEMBER(GpuLightGridCell, power)}},
      {"GpuLightGridEntry",
       sizeof(gpu::GpuLightGridEntry),
       {LANTERN_MEMBER(GpuLightGridEntry, light), LANTERN_MEMBER(GpuLightGridEntry, threshold),
        LANTERN_MEMBER(GpuLightGridEntry, alias)}},
      {"PresampledLight",
       sizeof(gpu::PresampledLight),
       {LANTERN_MEMBER(PresampledLight, light), LANTERN_MEMBER(PresampledLight, index),
        LANTERN_MEMBER(PresampledLight, pdf), LANTERN_MEMBER(PresampledLight, grid_cell)}},
      {"DenoisePush",
       sizeof(gpu::DenoisePush),
       {LANTERN_MEMBER(DenoisePush, width), LANTERN_MEMBER(DenoisePush, height),
        LANTERN_MEMBER(DenoisePush, flags), LANTERN_MEMBER(DenoisePush, step),
        LANTERN_MEMBER(DenoisePush, color_alpha), LANTERN_MEMBER(DenoisePush, moments_alpha),
        LANTERN_MEMBER(DenoisePush, phi_luminance), LANTERN_MEMBER(DenoisePush, phi_normal),
        LANTERN_MEMBER(DenoisePush, phi_depth), LANTERN_MEMBER(DenoisePush, firefly),
        LANTERN_MEMBER(DenoisePush, max_history), LANTERN_MEMBER(DenoisePush, sky_distance),
        LANTERN_MEMBER(DenoisePush, similarity), LANTERN_MEMBER(DenoisePush, neighbour_clamp),
        LANTERN_MEMBER(DenoisePush, antilag), LANTERN_MEMBER(DenoisePush, stabilize),
        LANTERN_MEMBER(DenoisePush, stabilize_band), LANTERN_MEMBER(DenoisePush, repay),
        LANTERN_MEMBER(DenoisePush, pad0), LANTERN_MEMBER(DenoisePush, pad1),
        LANTERN_MEMBER(DenoisePush, pad2)}},
      {"UpscalePush",
       sizeof(gpu::UpscalePush),
       {LANTERN_MEMBER(UpscalePush, in_width), LANTERN_MEMBER(UpscalePush, in_height),
        LANTERN_MEMBER(UpscalePush, out_width), LANTERN_MEMBER(UpscalePush, out_height),
        LANTERN_MEMBER(UpscalePush, flags), LANTERN_MEMBER(UpscalePush, history_weight),
        LANTERN_MEMBER(UpscalePush, jitter)}},
      {"RestirSurface",
       sizeof(gpu::RestirSurface),
       {LANTERN_MEMBER(RestirSurface, position_depth), LANTERN_MEMBER(RestirSurface, packed),
        LANTERN_MEMBER(RestirSurface, material)}},
      {"RestirSimilarityKey",
       sizeof(gpu::RestirSimilarityKey),
       {LANTERN_MEMBER(RestirSimilarityKey, depth), LANTERN_MEMBER(RestirSimilarityKey, normal),
        LANTERN_MEMBER(RestirSimilarityKey, material),
        LANTERN_MEMBER(RestirSimilarityKey, roughness)}},
      {"FrameConstants",
       sizeof(gpu::FrameConstants),
       {LANTERN_MEMBER(FrameConstants, view_proj), LANTERN_MEMBER(FrameConstants, prev_view_proj),
        LANTERN_MEMBER(FrameConstants, inv_view_proj),
        LANTERN_MEMBER(FrameConstants, camera_position),
        LANTERN_MEMBER(FrameConstants, prev_camera_position), LANTERN_MEMBER(FrameConstants, frame),
        LANTERN_MEMBER(FrameConstants, counts), LANTERN_MEMBER(FrameConstants, environment),
        LANTERN_MEMBER(FrameConstants, history), LANTERN_MEMBER(FrameConstants, scene),
        LANTERN_MEMBER(FrameConstants, jitter), LANTERN_MEMBER(FrameConstants, media)}},
      {"VolumePush",
       sizeof(gpu::VolumePush),
       {LANTERN_MEMBER(VolumePush, width), LANTERN_MEMBER(VolumePush, height),
        LANTERN_MEMBER(VolumePush, samples), LANTERN_MEMBER(VolumePush, flags)}},
      {"GpuVertex",
       sizeof(gpu::GpuVertex),
       {LANTERN_MEMBER(GpuVertex, position_u), LANTERN_MEMBER(GpuVertex, normal_v)}},
      {"GpuMaterial",
       sizeof(gpu::GpuMaterial),
       {LANTERN_MEMBER(GpuMaterial, base_color), LANTERN_MEMBER(GpuMaterial, emission),
        LANTERN_MEMBER(GpuMaterial, params), LANTERN_MEMBER(GpuMaterial, textures)}},
      {"GpuInstance",
       sizeof(gpu::GpuInstance),
       {LANTERN_MEMBER(GpuInstance, object_to_world),
        LANTERN_MEMBER(GpuInstance, prev_object_to_world),
        LANTERN_MEMBER(GpuInstance, world_to_object), LANTERN_MEMBER(GpuInstance, geometry),
        LANTERN_MEMBER(GpuInstance, bvh)}},
      {"GpuTexture",
       sizeof(gpu::GpuTexture),
       {LANTERN_MEMBER(GpuTexture, size), LANTERN_MEMBER(GpuTexture, format),
        LANTERN_MEMBER(GpuTexture, transform_u), LANTERN_MEMBER(GpuTexture, transform_v)}},
      {"GpuTexturedEmitter",
       sizeof(gpu::GpuTexturedEmitter),
       {LANTERN_MEMBER(GpuTexturedEmitter, uv01), LANTERN_MEMBER(GpuTexturedEmitter, uv2_tex)}},
      {"GpuVolume",
       sizeof(gpu::GpuVolume),
       {LANTERN_MEMBER(GpuVolume, world_to_index), LANTERN_MEMBER(GpuVolume, index_to_world),
        LANTERN_MEMBER(GpuVolume, scattering), LANTERN_MEMBER(GpuVolume, absorption),
        LANTERN_MEMBER(GpuVolume, support_min), LANTERN_MEMBER(GpuVolume, support_max),
        LANTERN_MEMBER(GpuVolume, cell_origin), LANTERN_MEMBER(GpuVolume, cells),
        LANTERN_MEMBER(GpuVolume, motion), LANTERN_MEMBER(GpuVolume, motion_inverse)}},
      {"GpuVolumeCell",
       sizeof(gpu::GpuVolumeCell),
       {LANTERN_MEMBER(GpuVolumeCell, brick), LANTERN_MEMBER(GpuVolumeCell, max_density),
        LANTERN_MEMBER(GpuVolumeCell, min_density), LANTERN_MEMBER(GpuVolumeCell, pad0)}},
      {"VolumeReservoir",
       sizeof(gpu::VolumeReservoir),
       {LANTERN_MEMBER(VolumeReservoir, scatter), LANTERN_MEMBER(VolumeReservoir, ray),
        LANTERN_MEMBER(VolumeReservoir, M), LANTERN_MEMBER(VolumeReservoir, target),
        LANTERN_MEMBER(VolumeReservoir, light), LANTERN_MEMBER(VolumeReservoir, medium)}},
      {"VolumeRestirPush",
       sizeof(gpu::VolumeRestirPush),
       {LANTERN_MEMBER(VolumeRestirPush, width), LANTERN_MEMBER(VolumeRestirPush, height),
        LANTERN_MEMBER(VolumeRestirPush, candidates), LANTERN_MEMBER(VolumeRestirPush, flags),
        LANTERN_MEMBER(VolumeRestirPush, neighbours), LANTERN_MEMBER(VolumeRestirPush, radius),
        LANTERN_MEMBER(VolumeRestirPush, m_cap),
        LANTERN_MEMBER(VolumeRestirPush, bias_correction)}},
      {"VolumeDda",
       sizeof(gpu::VolumeDda),
       {LANTERN_MEMBER(VolumeDda, t_next), LANTERN_MEMBER(VolumeDda, t_delta),
        LANTERN_MEMBER(VolumeDda, cell), LANTERN_MEMBER(VolumeDda, step)}},
      {"BvhNode",
       sizeof(gpu::BvhNode),
       {LANTERN_MEMBER(BvhNode, bounds_min), LANTERN_MEMBER(BvhNode, bounds_max)}},
      {"BvhTriangle",
       sizeof(gpu::BvhTriangle),
       {LANTERN_MEMBER(BvhTriangle, v0), LANTERN_MEMBER(BvhTriangle, e1),
        LANTERN_MEMBER(BvhTriangle, e2)}},
      {"BvhInstance",
       sizeof(gpu::BvhInstance),
       {LANTERN_MEMBER(BvhInstance, object_to_world), LANTERN_MEMBER(BvhInstance, world_to_object),
        LANTERN_MEMBER(BvhInstance, node_offset), LANTERN_MEMBER(BvhInstance, triangle_offset),
        LANTERN_MEMBER(BvhInstance, user_id), LANTERN_MEMBER(BvhInstance, flags)}},
      {"BvhSceneHeader",
       sizeof(gpu::BvhSceneHeader),
       {LANTERN_MEMBER(BvhSceneHeader, tlas_node_offset),
        LANTERN_MEMBER(BvhSceneHeader, tlas_node_count),
        LANTERN_MEMBER(BvhSceneHeader, instance_count),
        LANTERN_MEMBER(BvhSceneHeader, triangle_count)}},
      {"HostShadowRay",
       sizeof(gpu::HostShadowRay),
       {LANTERN_MEMBER(HostShadowRay, origin), LANTERN_MEMBER(HostShadowRay, direction),
        LANTERN_MEMBER(HostShadowRay, tfar), LANTERN_MEMBER(HostShadowRay, mask),
        LANTERN_MEMBER(HostShadowRay, id), LANTERN_MEMBER(HostShadowRay, flags)}},
      {"HostClosestRay",
       sizeof(gpu::HostClosestRay),
       {LANTERN_MEMBER(HostClosestRay, ray), LANTERN_MEMBER(HostClosestRay, ng_x),
        LANTERN_MEMBER(HostClosestRay, ng_y), LANTERN_MEMBER(HostClosestRay, ng_z),
        LANTERN_MEMBER(HostClosestRay, u), LANTERN_MEMBER(HostClosestRay, v),
        LANTERN_MEMBER(HostClosestRay, primitive), LANTERN_MEMBER(HostClosestRay, instance),
        LANTERN_MEMBER(HostClosestRay, instance_id)}},
      {"BvhRay",
       sizeof(gpu::BvhRay),
       {LANTERN_MEMBER(BvhRay, origin), LANTERN_MEMBER(BvhRay, direction)}},
      {"BvhHit",
       sizeof(gpu::BvhHit),
       {LANTERN_MEMBER(BvhHit, t), LANTERN_MEMBER(BvhHit, u), LANTERN_MEMBER(BvhHit, v),
        LANTERN_MEMBER(BvhHit, instance), LANTERN_MEMBER(BvhHit, primitive),
        LANTERN_MEMBER(BvhHit, user_id), LANTERN_MEMBER(BvhHit, pad0),
        LANTERN_MEMBER(BvhHit, pad1)}},
  };
  return table;
}

#undef LANTERN_MEMBER

// The probe's struct layouts, read by the runtime's SPIR-V reflection (the one SPIR-V reader).
const runtime::ShaderReflection& probe() {
  static const runtime::ShaderReflection reflection = runtime::reflect_spirv(
      runtime::read_spirv_file(LANTERN_LAYOUT_PROBE_SPV), LANTERN_LAYOUT_PROBE_SPV);
  return reflection;
}

TEST(Layout, ProbeDeclaresStructsWithOffsets) {
  ASSERT_FALSE(probe().structs.empty()) << LANTERN_LAYOUT_PROBE_SPV;
  // The reader must see real decorations, not just names: AliasEntry.alias sits at byte 4.
  const runtime::StructLayout* alias = probe().find_struct("AliasEntry");
  ASSERT_NE(alias, nullptr);
  ASSERT_EQ(alias->member_offsets.size(), 4u);
  EXPECT_EQ(alias->member_names[1], "alias");
  EXPECT_EQ(alias->member_offsets[1], 4);
  EXPECT_EQ(alias->array_stride, 16);
}

TEST(Layout, CppMatchesSpirvForEverySharedStruct) {
  for (const StructLayout& cpp : cpp_layouts()) {
    SCOPED_TRACE(cpp.name);
    const runtime::StructLayout* found = probe().find_struct(cpp.name);
    ASSERT_NE(found, nullptr)
        << cpp.name << " is not in layout_probe.comp: declare a std430 buffer of it there";
    const runtime::StructLayout& spirv = *found;
    ASSERT_EQ(spirv.member_offsets.size(), cpp.members.size())
        << cpp.name << ": member count differs between GLSL and the table in layout_test.cpp";
    for (std::size_t i = 0; i < cpp.members.size(); ++i) {
      EXPECT_EQ(spirv.member_names[i], cpp.members[i].name) << cpp.name << " member " << i;
      EXPECT_EQ(spirv.member_offsets[i], static_cast<std::int64_t>(cpp.members[i].offset))
          << cpp.name << "." << cpp.members[i].name << ": SPIR-V Offset vs C++ offsetof";
    }
    EXPECT_EQ(spirv.array_stride, static_cast<std::int64_t>(cpp.size))
        << cpp.name << ": SPIR-V ArrayStride vs C++ sizeof";
  }
}

// The GLSL-visible text of a shared header: // comments and `#ifdef __cplusplus` blocks (C++-only
// helpers such as CPU views with pointers) removed; a matching #else part is kept.
std::string glsl_visible_text(const std::filesystem::path& header) {
  std::ifstream file(header);
  std::stringstream out;
  std::string line;
  int depth = 0;         // #if nesting depth
  int cpp_only_at = -1;  // depth of the open `#ifdef __cplusplus`, -1 when outside one
  static const std::regex directive(R"(^\s*#\s*(\w+)\s*(.*))");
  while (std::getline(file, line)) {
    line = line.substr(0, line.find("//"));
    std::smatch m;
    if (std::regex_search(line, m, directive)) {
      std::string name = m[1];
      if (name == "if" || name == "ifdef" || name == "ifndef") {
        ++depth;
        if (name == "ifdef" && m[2].str().find("__cplusplus") == 0 && cpp_only_at < 0)
          cpp_only_at = depth;
        continue;
      }
      if (name == "else" && depth == cpp_only_at) {
        cpp_only_at = -1;
        continue;
      }
      if (name == "endif") {
        if (depth == cpp_only_at) cpp_only_at = -1;
        --depth;
        continue;
      }
    }
    if (cpp_only_at < 0) out << line << '\n';
  }
  return out.str();
}

std::vector<std::string> regex_captures(const std::string& text, const std::regex& pattern) {
  std::vector<std::string> found;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), pattern);
       it != std::sregex_iterator(); ++it)
    found.push_back((*it)[1]);
  return found;
}

std::vector<std::filesystem::path> shared_headers() {
  std::vector<std::filesystem::path> headers;
  for (const auto& entry : std::filesystem::directory_iterator(
           std::filesystem::path(LANTERN_SOURCE_DIR) / "shaders/shared"))
    if (entry.path().extension() == ".h") headers.push_back(entry.path());
  return headers;
}

// Records the shaders fetch through rgba32ui texel views (the render graph's kGraphTexelFormat,
// the scene's texel rows) are whole texels, with their members at the offsets the fetch
// functions assume (scene_light(), scene_light_alias(), restir_surface_fetch(),
// reservoir_fetch(), restir.initial's presampled lights). The fetch order itself is GLSL: a wrong
// one shows in the images the ReSTIR, denoiser and integrator tests compare.
TEST(Layout, TexelFetchedRecordsAreWholeTexels) {
  EXPECT_EQ(sizeof(gpu::GpuLight), 16u * gpu::kGpuLightTexels);
  EXPECT_EQ(offsetof(gpu::GpuLight, radiance), 16u * (gpu::kGpuLightTexels - 1));
  EXPECT_EQ(sizeof(gpu::AliasEntry), 16u);
  EXPECT_EQ(offsetof(gpu::AliasEntry, threshold), 0u);
  EXPECT_EQ(offsetof(gpu::AliasEntry, alias), 4u);
  EXPECT_EQ(offsetof(gpu::AliasEntry, pdf), 8u);
  EXPECT_EQ(sizeof(gpu::RestirSurface), 16u * gpu::kRestirSurfaceTexels);
  EXPECT_EQ(offsetof(gpu::RestirSurface, packed), 16u);
  EXPECT_EQ(offsetof(gpu::RestirSurface, material), 32u);
  EXPECT_EQ(sizeof(gpu::PackedReservoir), 16u);
  EXPECT_EQ(offsetof(gpu::PackedReservoir, light_age), 0u);
  EXPECT_EQ(offsetof(gpu::PackedReservoir, uv), 4u);
  EXPECT_EQ(offsetof(gpu::PackedReservoir, W), 8u);
  EXPECT_EQ(offsetof(gpu::PackedReservoir, m_target), 12u);
  EXPECT_EQ(sizeof(gpu::PresampledLight), 16u * gpu::kPresampledLightTexels);
  EXPECT_EQ(offsetof(gpu::PresampledLight, index), 16u * gpu::kGpuLightTexels);
  EXPECT_EQ(offsetof(gpu::PresampledLight, pdf), 16u * gpu::kGpuLightTexels + 4u);
}

TEST(Layout, EverySharedHeaderStructIsChecked) {
  std::set<std::string> covered;
  for (const StructLayout& s : cpp_layouts()) covered.insert(s.name);
  static const std::regex declaration(R"(\bstruct\s+([A-Za-z_]\w*)\s*\{)");
  std::size_t structs = 0;
  for (const std::filesystem::path& header : shared_headers()) {
    for (const std::string& name : regex_captures(glsl_visible_text(header), declaration)) {
      ++structs;
      EXPECT_TRUE(covered.count(name))
          << "struct " << name << " in " << header.filename().string()
          << " has no row in tests/layout/layout_test.cpp (add one, and a buffer of it in "
             "shaders/tests/layout_probe.comp)";
    }
  }
  EXPECT_FALSE(shared_headers().empty()) << "no headers under " << LANTERN_SOURCE_DIR;
  EXPECT_GE(structs, covered.size());
}

// Every shared header must be compiled as GLSL by the build: reachable through #include from
// at least one shader stage under shaders/ (all stages are compiled at build time).
TEST(Layout, EverySharedHeaderIsCompiledAsGlsl) {
  const std::filesystem::path shaders = std::filesystem::path(LANTERN_SOURCE_DIR) / "shaders";
  static const std::regex include(R"re(#\s*include\s+"([^"]+)")re");
  std::map<std::string, std::vector<std::string>>
      includes;  // path relative to shaders/ -> includes
  std::vector<std::string> stages;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(shaders)) {
    if (!entry.is_regular_file()) continue;
    std::string ext = entry.path().extension().string();
    std::string rel = std::filesystem::relative(entry.path(), shaders).generic_string();
    if (ext == ".comp" || ext == ".vert" || ext == ".frag" || ext == ".rgen") stages.push_back(rel);
    if (ext != ".h" && ext != ".glsl" && ext != ".comp" && ext != ".vert" && ext != ".frag" &&
        ext != ".rgen")
      continue;
    std::ifstream file(entry.path());
    std::stringstream text;
    text << file.rdbuf();
    for (const std::string& target : regex_captures(text.str(), include)) {
      // Shader includes resolve against shaders/ (-I) or the including file's folder.
      std::filesystem::path sibling = entry.path().parent_path() / target;
      includes[rel].push_back(std::filesystem::exists(sibling)
                                  ? std::filesystem::relative(sibling, shaders).generic_string()
                                  : target);
    }
  }
  std::set<std::string> reached(stages.begin(), stages.end());
  std::vector<std::string> frontier = stages;
  while (!frontier.empty()) {
    std::string file = frontier.back();
    frontier.pop_back();
    for (const std::string& next : includes[file])
      if (reached.insert(next).second) frontier.push_back(next);
  }
  for (const std::filesystem::path& header : shared_headers()) {
    std::string rel = "shared/" + header.filename().string();
    EXPECT_TRUE(reached.count(rel)) << rel
                                    << " is not included by any shader stage, so the build "
                                       "never compiles it as GLSL (include it in "
                                       "shaders/tests/layout_probe.comp)";
  }
}

}  // namespace
}  // namespace lantern::test
