// The scene's GPU buffers as every pass sees them: one storage buffer (or texel view) per slot in
// descriptor set 0, the slot being the binding number. GLSL declares them once
// (shaders/lib/scene_buffers.glsl, with lib/bvh_traverse.glsl and lib/environment.glsl); C++
// describes them once (lighting/scene/scene_buffers.h: graph name, shader name, access, texel
// view) and binds them by name through SceneHandles. A pass's own resources start at
// kPassBindingBase. Adding a scene buffer: a slot here, a row in scene_buffers.h, a block in
// scene_buffers.glsl. kSceneTlas is the one slot that is not a storage buffer: the ray-query
// backend's TLAS (scene.tlas_build builds it; only the rayquery shader variants declare it).
#ifndef LANTERN_SHARED_SCENE_BINDINGS_H
#define LANTERN_SHARED_SCENE_BINDINGS_H

#include "shared/lang.h"

LANTERN_BEGIN_SHARED

LANTERN_CONST uint kSceneFrameConstants = 0u;          // FrameConstants
LANTERN_CONST uint kSceneVertices = 1u;                // GpuVertex[]
LANTERN_CONST uint kSceneIndices = 2u;                 // uint[] (3 per triangle, mesh-relative)
LANTERN_CONST uint kSceneMaterials = 3u;               // GpuMaterial[]
LANTERN_CONST uint kSceneInstances = 4u;               // GpuInstance[] (with previous transforms)
LANTERN_CONST uint kSceneLights = 5u;                  // GpuLight[], this frame
LANTERN_CONST uint kSceneLightAlias = 6u;              // AliasEntry[] over the lights' power
LANTERN_CONST uint kSceneLightPreviousToCurrent = 7u;  // uint[] per last frame's light
LANTERN_CONST uint kSceneBvhHeader = 8u;               // BvhSceneHeader
LANTERN_CONST uint kSceneBvhNodes = 9u;                // BvhNode[] (rgba32ui texel view)
LANTERN_CONST uint kSceneBvhTriangles = 10u;           // BvhTriangle[] (rgba32ui texel view)
LANTERN_CONST uint kSceneBvhInstances = 11u;           // BvhInstance[] (rgba32ui texel view)
LANTERN_CONST uint kSceneEnvHeader = 12u;              // GpuEnvironment
LANTERN_CONST uint kSceneEnvTexels = 13u;              // vec4[] radiance texels
LANTERN_CONST uint kSceneEnvMarginal = 14u;            // AliasEntry[] over rows
LANTERN_CONST uint kSceneEnvConditional = 15u;         // AliasEntry[] per row over columns
LANTERN_CONST uint kSceneTextures = 16u;             // GpuTexture[] (shared/textures.h)
LANTERN_CONST uint kSceneTexels = 17u;               // uint[] every texture's mip chain
LANTERN_CONST uint kSceneTexturedEmitters = 18u;     // GpuTexturedEmitter[]
LANTERN_CONST uint kSceneVertexTangents = 19u;       // vec4[] per GpuVertex (normal-mapped levels)
LANTERN_CONST uint kSceneVertexTexcoords1 = 20u;     // vec2[] per GpuVertex (TEXCOORD_1 levels)
LANTERN_CONST uint kSceneVolumes = 21u;              // GpuVolume[] (shared/volume.h), this frame
LANTERN_CONST uint kSceneVolumeCells = 22u;          // GpuVolumeCell[] (majorant cells, bricks)
LANTERN_CONST uint kSceneVolumeValues = 23u;         // float[] brick voxels
LANTERN_CONST uint kSceneLightGrid = 24u;            // GpuLightGrid, cells, lights (light_grid.h)
LANTERN_CONST uint kSceneLightCells = 25u;           // uvec2[] per light: grid cell key, count
LANTERN_CONST uint kSceneTlas = 26u;  // accelerationStructureEXT (ray-query visibility only)
LANTERN_CONST uint kSceneBufferCount = 27u;

// First binding of a pass's own resources (set 0).
LANTERN_CONST uint kPassBindingBase = kSceneBufferCount;

LANTERN_END_SHARED

#endif
