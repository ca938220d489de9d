#version 460
// Layout probe: includes every shared header that declares GPU structs (so each compiles as GLSL
// at build time) and declares a std430 buffer of every shared struct. tests/layout/ reads the SPIR-V offsets and
// array strides glslang emits and compares them with C++ offsetof/sizeof.
#extension GL_GOOGLE_include_directive : require

#include "shared/alias_table.h"
#include "shared/brdf.h"
#include "shared/bvh.h"
#include "shared/color.h"
#include "shared/common_math.h"
#include "shared/denoise.h"
#include "shared/environment.h"
#include "shared/host_visibility.h"
#include "shared/lang.h"
#include "shared/light_grid.h"
#include "shared/lights.h"
#include "shared/reservoir.h"
#include "shared/reservoir_mis.h"
#include "shared/reservoir_pack.h"
#include "shared/restir.h"
#include "shared/light_eval.h"
#include "shared/rng.h"
#include "shared/sampling.h"
#include "shared/scene.h"
#include "shared/textures.h"
#include "shared/tonemap.h"
#include "shared/upscale.h"
#include "shared/volume.h"

GpuVolumeCell volume_fetch_cell(uint i);
float volume_fetch_value(uint i);
#include "shared/volume_grid.h"
#include "shared/volume_restir.h"

layout(local_size_x = 1) in;

// One buffer per struct; the struct name is the SPIR-V OpName the test looks up.
layout(std430, binding = 0) buffer AliasEntryProbe { AliasEntry alias_entries[]; };
layout(std430, binding = 1) buffer GpuLightProbe { GpuLight gpu_lights[]; };
layout(std430, binding = 2) buffer LightSampleProbe { LightSample light_samples[]; };
layout(std430, binding = 3) buffer ReservoirProbe { Reservoir reservoirs[]; };
layout(std430, binding = 4) buffer PackedReservoirProbe { PackedReservoir packed_reservoirs[]; };
layout(std430, binding = 5) buffer FrameConstantsProbe { FrameConstants frame_constants[]; };
layout(std430, binding = 6) buffer GpuVertexProbe { GpuVertex gpu_vertices[]; };
layout(std430, binding = 7) buffer GpuMaterialProbe { GpuMaterial gpu_materials[]; };
layout(std430, binding = 8) buffer GpuInstanceProbe { GpuInstance gpu_instances[]; };
layout(std430, binding = 9) buffer BvhNodeProbe { BvhNode bvh_nodes[]; };
layout(std430, binding = 10) buffer BvhTriangleProbe { BvhTriangle bvh_triangles[]; };
layout(std430, binding = 11) buffer BvhInstanceProbe { BvhInstance bvh_instances[]; };
layout(std430, binding = 12) buffer BvhSceneHeaderProbe { BvhSceneHeader bvh_headers[]; };
layout(std430, binding = 13) buffer BvhRayProbe { BvhRay bvh_rays[]; };
layout(std430, binding = 14) buffer BvhHitProbe { BvhHit bvh_hits[]; };
layout(std430, binding = 15) buffer RestirPushProbe { RestirPush restir_pushes[]; };
layout(std430, binding = 16) buffer RestirSurfaceProbe { RestirSurface restir_surfaces[]; };
layout(std430, binding = 17) buffer GpuEnvironmentProbe { GpuEnvironment gpu_environments[]; };
layout(std430, binding = 18) buffer PresampledLightProbe { PresampledLight presampled_lights[]; };
layout(std430, binding = 19) buffer DenoisePushProbe { DenoisePush denoise_pushes[]; };
layout(std430, binding = 20) buffer UpscalePushProbe { UpscalePush upscale_pushes[]; };
layout(std430, binding = 21) buffer GpuTextureProbe { GpuTexture gpu_textures[]; };
layout(std430, binding = 22) buffer GpuTexturedEmitterProbe { GpuTexturedEmitter gpu_textured_emitters[]; };
layout(std430, binding = 23) buffer GpuVolumeProbe { GpuVolume gpu_volumes[]; };
layout(std430, binding = 24) buffer GpuVolumeCellProbe { GpuVolumeCell gpu_volume_cells[]; };
layout(std430, binding = 25) buffer VolumeDdaProbe { VolumeDda volume_ddas[]; };
layout(std430, binding = 26) buffer VolumePushProbe { VolumePush volume_pushes[]; };
layout(std430, binding = 27) buffer VolumeReservoirProbe { VolumeReservoir volume_reservoirs[]; };
layout(std430, binding = 28) buffer VolumeRestirPushProbe { VolumeRestirPush volume_restir_pushes[]; };
layout(std430, binding = 29) buffer HostShadowRayProbe { HostShadowRay host_shadow_rays[]; };
layout(std430, binding = 30) buffer RestirSimilarityKeyProbe { RestirSimilarityKey restir_similarity_keys[]; };
layout(std430, binding = 31) buffer HostClosestRayProbe { HostClosestRay host_closest_rays[]; };
layout(std430, binding = 32) buffer GpuLightGridProbe { GpuLightGrid gpu_light_grids[]; };
layout(std430, binding = 33) buffer GpuLightGridCellProbe { GpuLightGridCell gpu_light_grid_cells[]; };
layout(std430, binding = 34) buffer GpuLightGridEntryProbe { GpuLightGridEntry gpu_light_grid_entries[]; };

void main() {
  // Touch every buffer so no declaration is optimised away.
  alias_entries[0] = alias_entries[1];
  gpu_light_grids[0] = gpu_light_grids[1];
  gpu_light_grid_cells[0] = gpu_light_grid_cells[1];
  gpu_light_grid_entries[0] = gpu_light_grid_entries[1];
  denoise_pushes[0] = denoise_pushes[1];
  restir_similarity_keys[0] = restir_similarity_keys[1];
  upscale_pushes[0] = upscale_pushes[1];
  gpu_lights[0] = gpu_lights[1];
  light_samples[0] = light_samples[1];
  reservoirs[0] = reservoirs[1];
  packed_reservoirs[0] = packed_reservoirs[1];
  frame_constants[0] = frame_constants[1];
  gpu_vertices[0] = gpu_vertices[1];
  gpu_materials[0] = gpu_materials[1];
  gpu_instances[0] = gpu_instances[1];
  bvh_nodes[0] = bvh_nodes[1];
  bvh_triangles[0] = bvh_triangles[1];
  bvh_instances[0] = bvh_instances[1];
  bvh_headers[0] = bvh_headers[1];
  bvh_rays[0] = bvh_rays[1];
  bvh_hits[0] = bvh_hits[1];
  restir_pushes[0] = restir_pushes[1];
  restir_surfaces[0] = restir_surfaces[1];
  gpu_environments[0] = gpu_environments[1];
  presampled_lights[0] = presampled_lights[1];
  gpu_textures[0] = gpu_textures[1];
  gpu_textured_emitters[0] = gpu_textured_emitters[1];
  gpu_volumes[0] = gpu_volumes[1];
  gpu_volume_cells[0] = gpu_volume_cells[1];
  volume_ddas[0] = volume_ddas[1];
  volume_pushes[0] = volume_pushes[1];
  volume_reservoirs[0] = volume_reservoirs[1];
  volume_restir_pushes[0] = volume_restir_pushes[1];
  host_shadow_rays[0] = host_shadow_rays[1];
  host_closest_rays[0] = host_closest_rays[1];
}
