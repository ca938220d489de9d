// GPU records of the scene a frame renders: per-frame constants, vertices, materials and
// instances. Built by lighting/scene from the frame snapshot; read by the G-buffer, visibility,
// ReSTIR, baseline and reference passes.
#ifndef LANTERN_SHARED_SCENE_H
#define LANTERN_SHARED_SCENE_H

#include "shared/lang.h"

LANTERN_BEGIN_SHARED

// A texture slot that holds no texture.
LANTERN_CONST uint kNoTexture = 0xffffffffu;
// instance_id value in the G-buffer where no geometry was hit (sky).
LANTERN_CONST uint kNoInstance = 0xffffffffu;

struct FrameConstants {
  mat4 view_proj;          // world -> clip, this frame (no jitter)
  mat4 prev_view_proj;     // world -> clip, previous frame (equals view_proj after a cut)
  mat4 inv_view_proj;      // clip -> world, this frame
  vec4 camera_position;    // xyz world position; w: vertical field of view (radians)
  vec4 prev_camera_position;
  uvec4 frame;             // x, y: render size; z: frame index; w: seed (every pass reads these
                           // here: push constants do not repeat them)
  uvec4 counts;            // x: lights in the alias table (0: none can be sampled); y: instances;
                           // z: emissive triangles; w: 1 after a camera cut
  vec4 environment;        // rgb: uniform sky radiance scale; w: exposure
  uvec4 history;           // x: last frame's lights (entries of light_previous_to_current); y: 1
                           // when every light kept its index (the map is the identity and is
                           // not read: scene_light_from_previous); zw: 0
  vec4 scene;              // x: radius of the world's bounding sphere (directional and environment
                           // shadow rays end kDirectionalShadowRadii radii away); y: the
                           // emissive triangles' share of the lights' power (the first of the
                           // light draw's two groups, shared/alias_table.h); zw: 0
  vec4 jitter;             // xy: this frame's G-buffer sample offset from the pixel centres, in
                           // pixels (+x right, +y down; 0 unless upscaling); zw: last frame's
                           // (gbuffer.h: gbuffer_jitter_clip, and the motion convention)
  uvec4 media;             // x: volumes in scene_volumes (0: no medium, every transmittance is 1
                           // without a loop); yzw: 0
};
LANTERN_STATIC_SIZE(FrameConstants, 3 * 64 + 9 * 16);

struct GpuVertex {
  vec4 position_u;  // xyz object-space position; w: texture u
  vec4 normal_v;    // xyz object-space normal; w: texture v
};
LANTERN_STATIC_SIZE(GpuVertex, 32);

struct GpuMaterial {
  vec4 base_color;  // rgb linear albedo; a: alpha (opaque only this round)
  vec4 emission;    // rgb emitted radiance W/(sr m^2), one-sided (front face); w: unused
  vec4 params;      // x: perceptual roughness; y: metallic; z: specular factor; w: unused
  uvec4 textures;   // x: base color; y: metallic-roughness; z: emissive; w: normal (kNoTexture)
};
LANTERN_STATIC_SIZE(GpuMaterial, 64);

struct GpuInstance {
  mat4 object_to_world;
  mat4 prev_object_to_world;  // equals object_to_world for static instances and on first frame
  mat4 world_to_object;
  uvec4 geometry;             // x: material; y: first index; z: index count; w: first vertex
  uvec4 bvh;                  // x: BLAS root node; y: first emissive light or kInvalidLight;
                              // z: emission scale (float bits: uintBitsToFloat; the snapshot's
                              // flicker, multiplies the material emission); w: 0
};
LANTERN_STATIC_SIZE(GpuInstance, 3 * 64 + 32);

LANTERN_END_SHARED

#endif
