// gbuffer.resolve (fragment stage): the G-buffer images of shaders/shared/gbuffer.h as colour
// attachments from gbuffer.visibility (storage image: the gbuffer.cull list entry of the closest
// triangle, or kNoInstance) and that entry's (instance, triangle) (gbuffer_triangles); one
// full-screen triangle. The "hosthits" variant (LANTERN_GBUFFER_HOST_HITS, the host method)
// has no visibility image: gbuffer_triangles holds one record per pixel, row-major, written by
// the host pass gbuffer.host (instance kNoInstance = sky). A raster pass rather than compute: colour-attachment writes cost lavapipe
// much less than storage-image stores (the compute form measured 2-2.7x slower).
#version 460
#extension GL_GOOGLE_include_directive : require

#include "lib/scene_buffers.glsl"

layout(std430, binding = PASS_BINDING(0)) restrict readonly buffer TriangleBuffer {
  uvec2 t[];
} gbuffer_triangles;
#ifndef LANTERN_GBUFFER_HOST_HITS
layout(binding = PASS_BINDING(1), r32ui) uniform restrict readonly uimage2D gbuffer_visibility;
#endif

#include "gbuffer/gbuffer_material.glsl"

// The scene has material textures (GBufferPassOptions::textured): else the textured path is
// compiled out.
layout(constant_id = 0) const bool kTextured = false;

#include "gbuffer/gbuffer_resolve.glsl"

layout(location = 0) out vec4 out_position;
layout(location = 1) out vec4 out_normal;
layout(location = 2) out vec4 out_albedo_roughness;
layout(location = 3) out vec4 out_emission_metallic;
layout(location = 4) out uvec4 out_ids;
layout(location = 5) out vec4 out_motion;

void main() {
  uvec2 pixel = uvec2(gl_FragCoord.xy);
#ifdef LANTERN_GBUFFER_HOST_HITS
  uvec2 hit = gbuffer_triangles.t[pixel.y * frame_constants.frame.frame.x + pixel.x];
  GBufferTexel g = hit.x == kNoInstance ? gbuffer_sky_texel() : gbuffer_resolve_texel(pixel, hit);
#else
  uint entry = imageLoad(gbuffer_visibility, ivec2(pixel)).x;
  GBufferTexel g = entry == kNoInstance ? gbuffer_sky_texel()
                                        : gbuffer_resolve_texel(pixel, gbuffer_triangles.t[entry]);
#endif
  out_position = g.position;
  out_normal = g.normal;
  out_albedo_roughness = g.albedo_roughness;
  out_emission_metallic = g.emission_metallic;
  out_ids = g.ids;
  out_motion = g.motion;
}
