// The material at a G-buffer surface point, textures applied (both G-buffer methods call it):
// base colour x baseColorTexture (sRGB-decoded; alpha for the cutout), roughness x G and metallic
// x B of metallicRoughnessTexture, emission x emissiveTexture, and the shading normal perturbed
// by normalTexture in the triangle's tangent frame. The tangent frame is the triangle's own
// (dp/du, dp/dv from its corners' positions and texcoords), Gram-Schmidt orthogonalised against
// the interpolated normal, bitangent = sign x cross(n, t) -- MikkTSpace's construction for a
// triangle whose neighbours share its uv mapping (flat and planar-mapped meshes; MikkTSpace also
// averages tangents across smooth vertices, which this does not). The texture level of detail
// comes from the pixel's texcoord footprint `duv` (du/dx, dv/dx, du/dy, dv/dy): raster
// derivatives in the forward pass, ray differentials in the visibility resolve.
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

// Texture record `texture` at uv, level of detail from the pixel footprint `duv` (through the
// texture transform's linear part). The record is loaded once (every storage-buffer load is a
// per-lane gather on lavapipe).
vec4 gbuffer_texture(uint texture, vec2 uv, vec4 duv) {
  GpuTexture t = scene_textures.t[texture];
  vec2 ax = vec2(dot(t.transform_u.xy, duv.xy), dot(t.transform_v.xy, duv.xy));
  vec2 ay = vec2(dot(t.transform_u.xy, duv.zw), dot(t.transform_v.xy, duv.zw));
  return texture_sample_record(t, uv, texture_lod(t, vec4(ax, ay)));
}

// True when the material is alpha-tested (MASK) and the point is cut out.
bool gbuffer_alpha_cut(GpuMaterial m, vec2 uv, vec4 duv) {
  float cutoff = m.params.w;
  if (!(cutoff > 0.0)) return false;
  float alpha = m.base_color.a;
  if (m.textures.x != kNoTexture) alpha *= gbuffer_texture(m.textures.x, uv, duv).a;
  return alpha < cutoff;
}

// `ns`: interpolated shading normal (unit, on the viewer's side); dp1, dp2: world edges p1 - p0,
// p2 - p0 of the triangle and duv1, duv2 their texcoord differences.
GBufferMaterial gbuffer_material(GpuMaterial m, vec2 uv, vec4 duv, vec3 ns, vec3 dp1, vec3 dp2,
                                 vec2 duv1, vec2 duv2) {
  GBufferMaterial g;
  g.base_color = m.base_color.rgb;
  g.alpha = m.base_color.a;
  g.roughness = m.params.x;
  g.metallic = m.params.y;
  g.emission = m.emission.rgb;
  g.shading_normal = ns;
  if (m.textures.x != kNoTexture) {
    vec4 c = gbuffer_texture(m.textures.x, uv, duv);
    g.base_color *= c.rgb;
    g.alpha *= c.a;
  }
  if (m.textures.y != kNoTexture) {
    vec4 c = gbuffer_texture(m.textures.y, uv, duv);
    g.roughness *= c.g;
    g.metallic *= c.b;
  }
  if (m.textures.z != kNoTexture) g.emission *= gbuffer_texture(m.textures.z, uv, duv).rgb;
  if (m.textures.w != kNoTexture) {
    float r = duv1.x * duv2.y - duv1.y * duv2.x;
    vec3 t = (dp1 * duv2.y - dp2 * duv1.y) * r;
    vec3 b_uv = (dp2 * duv1.x - dp1 * duv2.x) * r;
    t -= ns * dot(ns, t);
    float t_len2 = dot(t, t);
    if (r != 0.0 && t_len2 > 0.0 && is_finite(t_len2)) {
      t *= inversesqrt(t_len2);
      // glTF tangent space: +Y is "up" in the image, i.e. towards -v (glTF's v runs down).
      float sign = dot(cross(ns, t), b_uv) < 0.0 ? 1.0 : -1.0;
      vec3 b = sign * cross(ns, t);
      vec3 n_tex = gbuffer_texture(m.textures.w, uv, duv).xyz * 2.0 - 1.0;
      n_tex.xy *= m.emission.w;  // normalTexture.scale
      vec3 n = t * n_tex.x + b * n_tex.y + ns * n_tex.z;
      float n_len2 = dot(n, n);
      if (n_len2 > 0.0 && is_finite(n_len2)) g.shading_normal = n * inversesqrt(n_len2);
    }
  }
  return g;
}

#endif
