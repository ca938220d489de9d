// Material textures on the GPU: one record per material texture slot (image + glTF sampler +
// KHR_texture_transform + texcoord set) and one scene array of packed texels holding every
// image's mip chain, level 0 first. Sampled in software (lib/textures.glsl): bilinear within a
// level, linear between levels, glTF wrap modes. lighting/textures/texture_set.h builds both
// arrays; the pure math both sides use (wrap, transform, sRGB decode, level of detail) is here.
#ifndef LANTERN_SHARED_TEXTURES_H
#define LANTERN_SHARED_TEXTURES_H

#include "shared/lang.h"
#include "shared/scene.h"

LANTERN_BEGIN_SHARED

// Texel encodings (GpuTexture.format.x).
// Colour (sRGB) images are decoded to linear at load and kept as half floats: an sRGB8 texel
// decoded in the shader (three pow per texel, four texels per bilinear tap) measured 1.8x the cost
// of a half texel on lavapipe (tests/textures/texture_sampling_bench: 53.5 vs 29.2 ns per
// bilinear sample), for 2x the memory.
LANTERN_CONST uint kTexelUnorm8 = 0u;  // one uint per texel, RGBA8 (packUnorm4x8), linear data
LANTERN_CONST uint kTexelHalf = 1u;    // two uints per texel, RGBA16F (packHalf2x16: RG, BA),
                                       // linear: colour (sRGB-decoded) and HDR images

// glTF sampler wrap modes (GpuTexture.format.y / z).
LANTERN_CONST uint kWrapRepeat = 0u;
LANTERN_CONST uint kWrapClamp = 1u;
LANTERN_CONST uint kWrapMirror = 2u;

// GpuTexture.format.w bits.
LANTERN_CONST uint kFilterMagLinear = 1u;  // bilinear when magnified (else nearest)
LANTERN_CONST uint kFilterMinLinear = 2u;  // bilinear within a level when minified
LANTERN_CONST uint kFilterMipLinear = 4u;  // blend two levels (else the nearest level)
LANTERN_CONST uint kFilterMipmaps = 8u;    // minification uses the mip chain (else level 0)

// Largest accepted image side (texels) and total texel memory of a level: beyond these a level
// is refused at load (lantern::InputError naming the image), not silently downscaled.
LANTERN_CONST uint kMaxTextureSide = 8192u;
LANTERN_CONST uint kMaxTexelBytes = 128u * 1024u * 1024u;  // one storage binding on lavapipe

struct GpuTexture {
  uvec4 size;        // x: width, y: height (level 0); z: mip levels; w: first word of level 0
  uvec4 format;      // x: texel encoding; y: wrap s; z: wrap t; w: filter bits
  vec4 transform_u;  // u' = dot(transform_u.xyz, (u, v, 1)) (KHR_texture_transform); w: texcoord
  vec4 transform_v;  // v' = dot(transform_v.xyz, (u, v, 1)); w: unused
};
LANTERN_STATIC_SIZE(GpuTexture, 64);

// The texcoord set (0: TEXCOORD_0, 1: TEXCOORD_1) a texture record samples.
LANTERN_FUNC uint texture_texcoord_set(GpuTexture t) {
  return t.transform_u.w == 1.0f ? 1u : 0u;
}

// A material texture slot's uv: the texture transform applied to the mesh's texcoords.
LANTERN_FUNC vec2 texture_transform_uv(GpuTexture t, vec2 uv) {
  vec3 h = vec3(uv.x, uv.y, 1.0f);
  return vec2(dot(vec3(t.transform_u), h), dot(vec3(t.transform_v), h));
}

// Integer texel coordinate i (any integer) wrapped into [0, n) by glTF mode `mode`.
LANTERN_FUNC int texture_wrap(int i, int n, uint mode) {
  if (mode == kWrapClamp) {
    return clamp(i, 0, n - 1);
  }
  if (mode == kWrapMirror) {
    int period = 2 * n;
    int k = i % period;
    if (k < 0) {
      k += period;
    }
    return k < n ? k : period - 1 - k;
  }
  int k = i % n;
  return k < 0 ? k + n : k;
}

// Exact sRGB electro-optical transfer (IEC 61966-2-1): encoded [0,1] -> linear.
LANTERN_FUNC float srgb_to_linear(float c) {
  return c <= 0.04045f ? c / 12.92f : pow((c + 0.055f) / 1.055f, 2.4f);
}

// Level of detail from the texcoord footprint of one pixel (du/dx, dv/dx, du/dy, dv/dy in uv
// units, after the texture transform): log2 of the longer axis in level-0 texels, >= 0.
LANTERN_FUNC float texture_lod(GpuTexture t, vec4 duv) {
  vec2 size = vec2(float(t.size.x), float(t.size.y));
  vec2 dx = vec2(duv.x, duv.y) * size;
  vec2 dy = vec2(duv.z, duv.w) * size;
  float rho2 = max(dot(dx, dx), dot(dy, dy));
  return rho2 > 1.0f ? 0.5f * log2(rho2) : 0.0f;
}

// Words one level of a w x h image takes in `format`.
LANTERN_FUNC uint texture_level_words(uint w, uint h, uint format) {
  return w * h * (format == kTexelHalf ? 2u : 1u);
}

// Whether any of the material's slots names a texture.
LANTERN_FUNC bool material_textured(GpuMaterial m) {
  return m.textures.x != kNoTexture || m.textures.y != kNoTexture || m.textures.z != kNoTexture ||
         m.textures.w != kNoTexture;
}

// The material an integrator shades a G-buffer pixel with: the record, but base colour,
// roughness and metallic from the G-buffer (albedo_roughness, emission_metallic.w) where the
// material is textured -- the G-buffer holds the textured values; an untextured material keeps
// its record's exact values (the G-buffer's albedo is half precision).
LANTERN_FUNC GpuMaterial material_at_gbuffer(GpuMaterial m, vec4 albedo_roughness, float metallic) {
  if (material_textured(m)) {
    m.base_color = vec4(albedo_roughness.x, albedo_roughness.y, albedo_roughness.z, m.base_color.w);
    m.params.x = albedo_roughness.w;
    m.params.y = metallic;
  }
  return m;
}

// The texcoords of one textured emissive triangle light, which a light record names by
// GpuLight.radiance.w = uintBitsToFloat(record + 1) (0: the light is not textured): its radiance
// at barycentrics (b1, b2) is radiance.rgb x the emissive texture at the interpolated uv.
struct GpuTexturedEmitter {
  vec4 uv01;     // xy: uv of vertex 0; zw: uv of vertex 1 (in the light's winding)
  vec4 uv2_tex;  // xy: uv of vertex 2; z: GpuTexture index (float bits); w: level of detail
};
LANTERN_STATIC_SIZE(GpuTexturedEmitter, 32);

LANTERN_END_SHARED

#endif
