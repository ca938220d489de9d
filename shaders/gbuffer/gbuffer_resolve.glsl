// gbuffer.resolve: one pixel of the G-buffer (shaders/shared/gbuffer.h) from the closest triangle
// (instance, triangle), as the forward raster would have interpolated it. The pixel-centre camera
// ray (baseline.comp's construction from inv_view_proj) meets the triangle's plane at barycentrics
// (b1, b2) (Moller-Trumbore in world space; the same perspective-correct weights the raster
// interpolates with); position, shading normal and the clip positions of gbuffer_point_motion are
// barycentric blends of the corners. Shading normals go through the cofactor of object_to_world
// (det times the inverse transpose: the direction of transpose(world_to_object) n up to sign, which
// the flip towards the geometric normal removes), so world_to_object is not loaded: on lavapipe
// every per-pixel load from a storage buffer is a per-lane gather, the cost of this pass. Needs the
// blocks frame_constants, scene_vertices, scene_indices, scene_materials and scene_instances
// declared by the includer. When the includer has included gbuffer/gbuffer_material.glsl and
// declares the specialisation constant kTextured, textured materials apply with the level of detail
// from ray differentials (the pixel's neighbours' rays against the triangle's plane) and
// gbuffer_resolve_alpha_cut is available.
#ifndef LANTERN_GBUFFER_RESOLVE_GLSL
#define LANTERN_GBUFFER_RESOLVE_GLSL

#include "gbuffer/gbuffer_push.h"
#include "shared/common_math.h"
#include "shared/gbuffer.h"
#include "shared/scene.h"

struct GBufferTexel {
  vec4 position;
  vec4 normal;
  vec4 albedo_roughness;
  vec4 emission_metallic;
  uvec4 ids;
  vec4 motion;
};

float gbuffer_finite_or_zero(float x) { return is_finite(x) ? x : 0.0; }
vec3 gbuffer_finite_or_zero(vec3 v) {
  return vec3(gbuffer_finite_or_zero(v.x), gbuffer_finite_or_zero(v.y),
              gbuffer_finite_or_zero(v.z));
}

GBufferTexel gbuffer_sky_texel() {
  GBufferTexel g;
  g.position = vec4(0.0);
  g.normal = vec4(0.0);
  g.albedo_roughness = vec4(0.0);
  g.emission_metallic = vec4(0.0);
  g.ids = uvec4(kNoInstance, kNoInstance, kNoInstance, 0u);
  g.motion = vec4(0.0);
  return g;
}

// Barycentrics (b1, b2) where the camera ray through image point `point` (pixels from the
// top-left; a pixel centre is pixel + 0.5) meets the plane of the world triangle (w0, w0 + e1,
// w0 + e2); the centroid when edge-on or degenerate.
vec2 gbuffer_ray_barycentrics(vec2 point, vec3 w0, vec3 e1, vec3 e2) {
  vec3 near_point;
  float far_t;
  vec3 dir = gbuffer_camera_ray(frame_constants.frame.inv_view_proj, point,
                                vec2(frame_constants.frame.frame.xy), near_point, far_t);
  vec3 origin = frame_constants.frame.camera_position.xyz;
  vec3 q = cross(dir, e2);
  float det = dot(e1, q);
  vec3 s = origin - w0;
  vec3 r = cross(s, e1);
  float b1 = dot(s, q) / det;
  float b2 = dot(dir, r) / det;
  if (!(is_finite(b1) && is_finite(b2))) return vec2(1.0 / 3.0);
  return vec2(b1, b2);
}

#ifdef LANTERN_GBUFFER_MATERIAL_GLSL
// Both texcoord sets and their pixel footprints at barycentrics b of the triangle with corner
// vertices i0, i1, i2 (world corner w0, edges e1, e2) seen at sample position `centre`: the
// footprint from the rays through the positions one pixel right and one down (ray differentials
// against the triangle's plane). Set 1 only where the level has TEXCOORD_1 (else zero).
GBufferTexcoords gbuffer_resolve_texcoords(vec2 centre, vec2 b, uint i0, uint i1, uint i2, vec3 w0,
                                           vec3 e1, vec3 e2) {
  vec2 bx = gbuffer_ray_barycentrics(centre + vec2(1.0, 0.0), w0, e1, e2) - b;
  vec2 by = gbuffer_ray_barycentrics(centre + vec2(0.0, 1.0), w0, e1, e2) - b;
  GBufferTexcoords tc;
  tc.uv[1] = vec2(0.0);
  tc.duv[1] = vec4(0.0);
  uint sets = scene_has_texcoords1() ? 2u : 1u;
  for (uint set = 0u; set < sets; ++set) {
    vec2 uv0 = scene_vertex_texcoord(i0, set);
    vec2 d1 = scene_vertex_texcoord(i1, set) - uv0;
    vec2 d2 = scene_vertex_texcoord(i2, set) - uv0;
    tc.uv[set] = uv0 + b.x * d1 + b.y * d2;
    tc.duv[set] = vec4(bx.x * d1 + bx.y * d2, by.x * d1 + by.y * d2);
  }
  return tc;
}

// Whether the alpha-tested material of `hit` cuts the surface out at `pixel` (gbuffer.visibility
// discards there, so the depth test keeps what lies behind).
bool gbuffer_resolve_alpha_cut(uvec2 pixel, uvec2 hit) {
  uvec4 geometry = scene_instances.i[hit.x].geometry;
  GpuMaterial material = scene_materials.m[geometry.x];
  if (!(material.params.w > 0.0)) return false;
  uint base = geometry.y + 3u * hit.y;
  uint i0 = geometry.w + scene_indices.i[base];
  uint i1 = geometry.w + scene_indices.i[base + 1u];
  uint i2 = geometry.w + scene_indices.i[base + 2u];
  mat4 object_to_world = scene_instances.i[hit.x].object_to_world;
  vec3 p0 = scene_vertices.v[i0].position_u.xyz;
  vec3 w0 = (object_to_world * vec4(p0, 1.0)).xyz;
  vec3 e1 = mat3(object_to_world) * (scene_vertices.v[i1].position_u.xyz - p0);
  vec3 e2 = mat3(object_to_world) * (scene_vertices.v[i2].position_u.xyz - p0);
  // The raster's (jittered) sample position of the pixel.
  vec2 centre = vec2(pixel) + 0.5 + frame_constants.frame.jitter.xy;
  vec2 b = gbuffer_ray_barycentrics(centre, w0, e1, e2);
  return gbuffer_alpha_cut(material, gbuffer_resolve_texcoords(centre, b, i0, i1, i2, w0, e1, e2));
}
#endif

// `pixel` from the top-left; `hit` = (instance, triangle) the raster found there.
GBufferTexel gbuffer_resolve_texel(uvec2 pixel, uvec2 hit) {
  uint instance = hit.x;
  uint primitive = hit.y;
  uvec4 geometry = scene_instances.i[instance].geometry;
  uint base = geometry.y + 3u * primitive;
  uint i0 = geometry.w + scene_indices.i[base];
  uint i1 = geometry.w + scene_indices.i[base + 1u];
  uint i2 = geometry.w + scene_indices.i[base + 2u];
  vec3 p0 = scene_vertices.v[i0].position_u.xyz;
  vec3 p1 = scene_vertices.v[i1].position_u.xyz;
  vec3 p2 = scene_vertices.v[i2].position_u.xyz;
  mat4 object_to_world = scene_instances.i[instance].object_to_world;
  mat3 linear = mat3(object_to_world);
  vec3 w0 = (object_to_world * vec4(p0, 1.0)).xyz;
  vec3 e1 = linear * (p1 - p0);
  vec3 e2 = linear * (p2 - p0);

  // Pixel-centre camera ray (through the jittered sample position).
  vec2 size = vec2(frame_constants.frame.frame.xy);
  vec2 sample_position = vec2(pixel) + 0.5 + frame_constants.frame.jitter.xy;
  vec3 origin = frame_constants.frame.camera_position.xyz;
  vec2 bary = gbuffer_ray_barycentrics(sample_position, w0, e1, e2);
  float b1 = bary.x;
  float b2 = bary.y;
  float b0 = 1.0 - b1 - b2;

  vec3 position = gbuffer_finite_or_zero(w0 + b1 * e1 + b2 * e2);
  vec3 to_camera = origin - position;
  // Cofactor matrix of `linear`: columns c0, c1, c2 with cof * n = det * inverse-transpose * n.
  mat3 cofactor = mat3(cross(linear[1], linear[2]), cross(linear[2], linear[0]),
                       cross(linear[0], linear[1]));
  float det_linear = dot(linear[0], cofactor[0]);
  vec3 ng = cross(e1, e2);
  if (det_linear < 0.0) ng = -ng;
  float ng_len2 = dot(ng, ng);
  ng = (ng_len2 > 0.0 && is_finite(ng_len2)) ? ng * inversesqrt(ng_len2) : vec3(0.0);
  bool front = dot(ng, to_camera) > 0.0;
  vec3 ng_facing = front ? ng : -ng;
  if (!(dot(ng_facing, ng_facing) > 0.0)) {  // degenerate triangle
    float d2 = dot(to_camera, to_camera);
    ng_facing = d2 > 0.0 ? to_camera * inversesqrt(d2) : vec3(0.0, 0.0, 1.0);
  }
  vec3 n_object = b0 * scene_vertices.v[i0].normal_v.xyz + b1 * scene_vertices.v[i1].normal_v.xyz +
                  b2 * scene_vertices.v[i2].normal_v.xyz;
  vec3 ns = cofactor * n_object;
  float ns_len2 = dot(ns, ns);
  ns = (ns_len2 > 0.0 && is_finite(ns_len2)) ? ns * inversesqrt(ns_len2) : ng_facing;
  if (dot(ns, ng_facing) < 0.0) ns = -ns;

  uint material_index = geometry.x;
  vec3 base_color = scene_materials.m[material_index].base_color.rgb;
  vec3 material_emission = scene_materials.m[material_index].emission.rgb;
  vec2 params = scene_materials.m[material_index].params.xy;
#ifdef LANTERN_GBUFFER_MATERIAL_GLSL
  if (kTextured) {
    GpuMaterial material = scene_materials.m[material_index];
    GBufferTexcoords tc =
        gbuffer_resolve_texcoords(sample_position, vec2(b1, b2), i0, i1, i2, w0, e1, e2);
    vec3 t = vec3(0.0), up = vec3(0.0);
    if (material.textures.w != kNoTexture) {
      uint set = scene_texture_set(material.textures.w);
      vec2 uv0 = scene_vertex_texcoord(i0, set);
      gbuffer_tangent_frame(i0, i1, i2, b1, b2, linear, e1, e2,
                            scene_vertex_texcoord(i1, set) - uv0,
                            scene_vertex_texcoord(i2, set) - uv0, t, up);
    }
    GBufferMaterial g = gbuffer_material(material, tc, ns, t, up);
    base_color = g.base_color;
    material_emission = g.emission;
    params = vec2(g.roughness, g.metallic);
    ns = g.shading_normal;
  }
#endif
  // The instance's emission scale (the snapshot's flicker, GpuInstance.bvh.z) multiplies the
  // material's emission, as it does for the light records sampled by the integrators.
  float emission_scale = uintBitsToFloat(scene_instances.i[instance].bvh.z);
  vec3 emission =
      front ? gbuffer_finite_or_zero(material_emission * emission_scale) : vec3(0.0);

  float view_depth =
      max(gbuffer_finite_or_zero((frame_constants.frame.view_proj * vec4(position, 1.0)).w),
          1e-30);

  // Both clip positions from the object-space point, through the same arithmetic
  // (gbuffer_point_motion: a point that did not move gets exactly 0).
  vec4 p_object = vec4(b0 * p0 + b1 * p1 + b2 * p2, 1.0);
  vec4 clip = frame_constants.frame.view_proj * (object_to_world * p_object);
  vec4 prev_clip = frame_constants.frame.prev_view_proj *
                   (scene_instances.i[instance].prev_object_to_world * p_object);
  vec4 motion = gbuffer_point_motion(clip, prev_clip, frame_constants.frame.jitter, size);

  GBufferTexel g;
  g.position = vec4(position, view_depth);
  g.normal = vec4(oct_encode(ns), oct_encode(ng_facing));
  g.albedo_roughness =
      vec4(gbuffer_finite_or_zero(base_color), gbuffer_finite_or_zero(params.x));
  g.emission_metallic = vec4(emission, gbuffer_finite_or_zero(params.y));
  g.ids = uvec4(instance, material_index, primitive, 0u);
  g.motion = motion;
  return g;
}

#endif
