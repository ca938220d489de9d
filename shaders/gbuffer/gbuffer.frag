// gbuffer (fragment stage): writes the G-buffer of shaders/shared/gbuffer.h for the closest surface
// (depth test LESS). Both normals are flipped to face the camera (the geometric one by the side the
// camera is on, the shading one into the geometric one's hemisphere); emission only where the
// camera sees the front face (counter-clockwise winding, GpuMaterial.emission is one-sided). Motion
// = gbuffer_point_motion of the interpolated clip positions (this frame's without jitter, last
// frame's); a point behind the previous camera gets kGBufferNoPreviousPixel (prev far off-screen).
// No output is NaN or Inf. With kTextured (the scene has material textures) the material's textures
// apply (gbuffer/gbuffer_material.glsl, level of detail from the raster's texcoord derivatives) and
// alpha-tested points are discarded; without, the textured path is compiled out.
#version 460
#extension GL_GOOGLE_include_directive : require

#include "gbuffer/gbuffer_push.h"
#include "shared/common_math.h"
#include "shared/gbuffer.h"
#include "lib/scene_buffers.glsl"
#include "gbuffer/gbuffer_material.glsl"

layout(constant_id = 0) const bool kTextured = false;

layout(location = 0) in vec3 in_world;
layout(location = 1) in vec3 in_shading_normal;
layout(location = 2) in vec4 in_prev_clip;
layout(location = 3) flat in vec3 in_geometric_normal;
layout(location = 4) flat in uvec3 in_ids;
layout(location = 5) in vec2 in_uv;
layout(location = 6) in vec2 in_uv1;
layout(location = 7) in vec4 in_clip;

layout(location = 0) out vec4 out_position;
layout(location = 1) out vec4 out_normal;
layout(location = 2) out vec4 out_albedo_roughness;
layout(location = 3) out vec4 out_emission_metallic;
layout(location = 4) out uvec4 out_ids;
layout(location = 5) out vec4 out_motion;

float finite_or_zero(float x) { return is_finite(x) ? x : 0.0; }
vec3 finite_or_zero(vec3 v) {
  return vec3(finite_or_zero(v.x), finite_or_zero(v.y), finite_or_zero(v.z));
}

void main() {
  vec3 position = finite_or_zero(in_world);
  vec3 to_camera = frame_constants.frame.camera_position.xyz - position;
  vec3 ng = in_geometric_normal;
  bool front = dot(ng, to_camera) > 0.0;
  vec3 ng_facing = front ? ng : -ng;
  if (!(dot(ng_facing, ng_facing) > 0.0)) {  // degenerate triangle (rasterises nothing anyway)
    float d2 = dot(to_camera, to_camera);
    ng_facing = d2 > 0.0 ? to_camera * inversesqrt(d2) : vec3(0.0, 0.0, 1.0);
  }
  vec3 ns = in_shading_normal;
  float ns_len2 = dot(ns, ns);
  ns = (ns_len2 > 0.0 && is_finite(ns_len2)) ? ns * inversesqrt(ns_len2) : ng_facing;
  if (dot(ns, ng_facing) < 0.0) ns = -ns;

  GpuMaterial material = scene_materials.m[in_ids.y];
  vec3 base_color = material.base_color.rgb;
  vec2 params = material.params.xy;
  vec3 material_emission = material.emission.rgb;
  if (kTextured) {
    // Derivatives first: none after the discard.
    GBufferTexcoords tc;
    tc.uv[0] = in_uv;
    tc.uv[1] = in_uv1;
    tc.duv[0] = vec4(dFdx(in_uv), dFdy(in_uv));
    tc.duv[1] = vec4(dFdx(in_uv1), dFdy(in_uv1));
    vec3 p_dx = dFdx(in_world);
    vec3 p_dy = dFdy(in_world);
    if (gbuffer_alpha_cut(material, tc)) discard;
    vec3 t = vec3(0.0), up = vec3(0.0);
    if (material.textures.w != kNoTexture) {
      // The triangle's vertices and the fragment's barycentrics, for its vertex tangents.
      uvec4 geometry = scene_instances.i[in_ids.x].geometry;
      uint base = geometry.y + 3u * in_ids.z;
      uint i0 = geometry.w + scene_indices.i[base];
      uint i1 = geometry.w + scene_indices.i[base + 1u];
      uint i2 = geometry.w + scene_indices.i[base + 2u];
      mat4 object_to_world = scene_instances.i[in_ids.x].object_to_world;
      mat3 linear = mat3(object_to_world);
      vec3 p0 = scene_vertices.v[i0].position_u.xyz;
      vec3 w0 = (object_to_world * vec4(p0, 1.0)).xyz;
      vec3 e1 = linear * (scene_vertices.v[i1].position_u.xyz - p0);
      vec3 e2 = linear * (scene_vertices.v[i2].position_u.xyz - p0);
      vec2 b = gbuffer_point_barycentrics(in_world, w0, e1, e2);
      uint set = scene_texture_set(material.textures.w);
      gbuffer_tangent_frame(i0, i1, i2, b.x, b.y, linear, p_dx, p_dy, tc.duv[set].xy,
                            tc.duv[set].zw, t, up);
    }
    GBufferMaterial g = gbuffer_material(material, tc, ns, t, up);
    base_color = g.base_color;
    params = vec2(g.roughness, g.metallic);
    material_emission = g.emission;
    ns = g.shading_normal;
  }
  // The instance's emission scale (flicker, GpuInstance.bvh.z) as in the light records.
  float emission_scale = uintBitsToFloat(scene_instances.i[in_ids.x].bvh.z);
  vec3 emission = front ? finite_or_zero(material_emission * emission_scale) : vec3(0.0);

  // gl_FragCoord.w = 1 / clip w, and clip w is the linear view depth (w = -z_view).
  float view_depth = max(finite_or_zero(1.0 / gl_FragCoord.w), 1e-30);

  vec4 motion = gbuffer_point_motion(in_clip, in_prev_clip, frame_constants.frame.jitter,
                                     vec2(frame_constants.frame.frame.xy));

  out_position = vec4(position, view_depth);
  out_normal = vec4(oct_encode(ns), oct_encode(ng_facing));
  out_albedo_roughness =
      vec4(finite_or_zero(base_color), finite_or_zero(params.x));
  out_emission_metallic = vec4(emission, finite_or_zero(params.y));
  out_ids = uvec4(in_ids, 0u);
  out_motion = motion;
}
