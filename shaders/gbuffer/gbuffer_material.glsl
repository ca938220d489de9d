// The material at a G-buffer surface point, textures applied (both G-buffer methods call it):
// base colour x baseColorTexture (sRGB-decoded; alpha for the cutout), roughness x G and metallic
// x B of metallicRoughnessTexture, emission x emissiveTexture, and the shading normal perturbed
// by normalTexture in the tangent frame of gbuffer_tangent_frame: the mesh's vertex tangents
// (the asset's TANGENT, or generated MikkTSpace-style at load: engine/scene/mesh_tangents.h)
// interpolated, else the triangle's own uv frame (dp/du, dp/dv); either is Gram-Schmidt
// orthogonalised against the shading normal, with the normal map's +Y = sign x cross(n, t) and
// the sign from the frame's "up" direction (glTF: decreasing v). Each texture samples its
// record's texcoord set (TEXCOORD_0 or _1) with the level of detail from that set's pixel
// footprint: raster derivatives in the forward pass, ray differentials in the visibility resolve.
// Needs lib/scene_buffers.glsl (scene_materials, the texture blocks).
#ifndef LANTERN_GBUFFER_MATERIAL_GLSL
#define LANTERN_GBUFFER_MATERIAL_GLSL

#include "shared/textures.h"

struct GBufferMaterial {
  vec3 base_color;
  float alpha;
  float roughness;
  float metallic;
  vec3 emission;  // before the front-face test and the instance's emission scale
  vec3 shading_normal;
};

// A surface point's texcoords in both sets (TEXCOORD_0, TEXCOORD_1; set 1 is zero in levels
// without it) and each set's pixel footprint (du/dx, dv/dx, du/dy, dv/dy).
struct GBufferTexcoords {
  vec2 uv[2];
  vec4 duv[2];
};

// Texture record `texture` at its texcoord set's uv, level of detail from that set's footprint
// (through the texture transform's linear part). The record is loaded once (every storage-buffer
// load is a per-lane gather on lavapipe).
vec4 gbuffer_texture(uint texture, GBufferTexcoords tc) {
  GpuTexture t = scene_textures.t[texture];
  uint set = texture_texcoord_set(t);
  vec4 duv = tc.duv[set];
  vec2 ax = vec2(dot(t.transform_u.xy, duv.xy), dot(t.transform_v.xy, duv.xy));
  vec2 ay = vec2(dot(t.transform_u.xy, duv.zw), dot(t.transform_v.xy, duv.zw));
  return texture_sample_record(t, tc.uv[set], texture_lod(t, vec4(ax, ay)));
}

// True when the material is alpha-tested (MASK) and the point is cut out.
bool gbuffer_alpha_cut(GpuMaterial m, GBufferTexcoords tc) {
  float cutoff = m.params.w;
  if (!(cutoff > 0.0)) return false;
  float alpha = m.base_color.a;
  if (m.textures.x != kNoTexture) alpha *= gbuffer_texture(m.textures.x, tc).a;
  return alpha < cutoff;
}

// Barycentrics (b1, b2) of point p in the plane of the triangle w0 + (0, e1, e2).
vec2 gbuffer_point_barycentrics(vec3 p, vec3 w0, vec3 e1, vec3 e2) {
  vec3 d = p - w0;
  float d00 = dot(e1, e1), d01 = dot(e1, e2), d11 = dot(e2, e2);
  float d20 = dot(d, e1), d21 = dot(d, e2);
  float denom = d00 * d11 - d01 * d01;
  vec2 b = vec2(d11 * d20 - d01 * d21, d00 * d21 - d01 * d20) / denom;
  return (is_finite(b.x) && is_finite(b.y)) ? b : vec2(1.0 / 3.0);
}

// The normal map's frame inputs at barycentrics (b1, b2) of the triangle with vertices i0, i1,
// i2 (scene_vertices indices) placed by `linear`: world-space tangent t (+u) and "up" (the
// normal map's +Y, decreasing v), neither orthogonalised. From the vertex tangents when the mesh
// has them (w != 0), else from the triangle's uv frame: dp1, dp2 are position differences
// (world edges, or screen derivatives) and duv1, duv2 the matching texcoord differences in the
// normal texture's set.
void gbuffer_tangent_frame(uint i0, uint i1, uint i2, float b1, float b2, mat3 linear, vec3 dp1,
                           vec3 dp2, vec2 duv1, vec2 duv2, out vec3 t, out vec3 up) {
  // Bounds: the tangent array is the vertices' length whenever a normal texture exists, which
  // is when this runs; the check keeps a stand-in from ever being read past its end.
  uint tangents = uint(scene_vertex_tangents.t.length());
  vec4 t0 = max(max(i0, i1), i2) < tangents ? scene_vertex_tangents.t[i0] : vec4(0.0);
  if (t0.w != 0.0) {
    float b0 = 1.0 - b1 - b2;
    vec3 t_object = b0 * t0.xyz + b1 * scene_vertex_tangents.t[i1].xyz +
                    b2 * scene_vertex_tangents.t[i2].xyz;
    vec3 n_object = b0 * scene_vertices.v[i0].normal_v.xyz +
                    b1 * scene_vertices.v[i1].normal_v.xyz + b2 * scene_vertices.v[i2].normal_v.xyz;
    t = linear * t_object;
    up = linear * (t0.w * cross(n_object, t_object));
    return;
  }
  float r = duv1.x * duv2.y - duv1.y * duv2.x;
  t = (dp1 * duv2.y - dp2 * duv1.y) * r;
  up = (dp1 * duv2.x - dp2 * duv1.x) * r;  // -dp/dv (glTF's v runs down the image)
}

// `ns`: interpolated shading normal (unit, on the viewer's side); t, up: gbuffer_tangent_frame's.
GBufferMaterial gbuffer_material(GpuMaterial m, GBufferTexcoords tc, vec3 ns, vec3 t, vec3 up) {
  GBufferMaterial g;
  g.base_color = m.base_color.rgb;
  g.alpha = m.base_color.a;
  g.roughness = m.params.x;
  g.metallic = m.params.y;
  g.emission = m.emission.rgb;
  g.shading_normal = ns;
  if (m.textures.x != kNoTexture) {
    vec4 c = gbuffer_texture(m.textures.x, tc);
    g.base_color *= c.rgb;
    g.alpha *= c.a;
  }
  if (m.textures.y != kNoTexture) {
    vec4 c = gbuffer_texture(m.textures.y, tc);
    g.roughness *= c.g;
    g.metallic *= c.b;
  }
  if (m.textures.z != kNoTexture) g.emission *= gbuffer_texture(m.textures.z, tc).rgb;
  if (m.textures.w != kNoTexture) {
    t -= ns * dot(ns, t);
    float t_len2 = dot(t, t);
    if (t_len2 > 0.0 && is_finite(t_len2)) {
      t *= inversesqrt(t_len2);
      float sign = dot(cross(ns, t), up) > 0.0 ? 1.0 : -1.0;
      vec3 b = sign * cross(ns, t);
      vec3 n_tex = gbuffer_texture(m.textures.w, tc).xyz * 2.0 - 1.0;
      n_tex.xy *= m.emission.w;  // normalTexture.scale
      vec3 n = t * n_tex.x + b * n_tex.y + ns * n_tex.z;
      float n_len2 = dot(n, n);
      if (n_len2 > 0.0 && is_finite(n_len2)) g.shading_normal = n * inversesqrt(n_len2);
    }
  }
  return g;
}

#endif
