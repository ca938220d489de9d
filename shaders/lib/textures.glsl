// Software texture sampling from the scene's texel array (shared/textures.h): texel fetch per
// encoding, bilinear filtering within a level with glTF wrap modes, linear blend between mip
// levels. Texels are linear (sRGB colour was decoded at load), so filtering is in linear light.
// Needs the blocks scene_textures (GpuTexture t[]) and scene_texels (uint w[]) declared by
// lib/scene_buffers.glsl. Why not a bindless array of sampled images: see
// lighting/textures/texture_set.h.
#ifndef LANTERN_LIB_TEXTURES_GLSL
#define LANTERN_LIB_TEXTURES_GLSL

#include "shared/textures.h"

vec4 texture_texel(uint first, uint format, uint index) {
  if (format == kTexelHalf) {
    uint a = scene_texels.w[first + 2u * index];
    uint b = scene_texels.w[first + 2u * index + 1u];
    return vec4(unpackHalf2x16(a), unpackHalf2x16(b));
  }
  return unpackUnorm4x8(scene_texels.w[first + index]);
}

// One level: `first` word, w x h texels; uv in level-0 normalised units.
vec4 texture_sample_level(GpuTexture t, uint first, uint w, uint h, vec2 uv, bool linear) {
  int iw = int(w);
  int ih = int(h);
  uint format = t.format.x;
  if (!linear) {
    int x = texture_wrap(int(floor(uv.x * float(w))), iw, t.format.y);
    int y = texture_wrap(int(floor(uv.y * float(h))), ih, t.format.z);
    return texture_texel(first, format, uint(y * iw + x));
  }
  vec2 p = uv * vec2(float(w), float(h)) - 0.5;
  vec2 f = fract(p);
  ivec2 i = ivec2(floor(p));
  int x0 = texture_wrap(i.x, iw, t.format.y);
  int x1 = texture_wrap(i.x + 1, iw, t.format.y);
  int y0 = texture_wrap(i.y, ih, t.format.z);
  int y1 = texture_wrap(i.y + 1, ih, t.format.z);
  vec4 c00 = texture_texel(first, format, uint(y0 * iw + x0));
  vec4 c10 = texture_texel(first, format, uint(y0 * iw + x1));
  vec4 c01 = texture_texel(first, format, uint(y1 * iw + x0));
  vec4 c11 = texture_texel(first, format, uint(y1 * iw + x1));
  return mix(mix(c00, c10, f.x), mix(c01, c11, f.x), f.y);
}

// Texture record `t` at texcoord `uv` (before the texture transform) with level of detail `lod`
// (shared/textures.h texture_lod; 0 = level 0). Linear RGBA.
vec4 texture_sample_record(GpuTexture t, vec2 uv, float lod) {
  uv = texture_transform_uv(t, uv);
  uint filter_bits = t.format.w;
  uint levels = t.size.z;
  bool minified = lod > 0.0;
  bool linear = (filter_bits & (minified ? kFilterMinLinear : kFilterMagLinear)) != 0u;
  float level = (minified && (filter_bits & kFilterMipmaps) != 0u)
                    ? min(lod, float(levels - 1u))
                    : 0.0;
  if ((filter_bits & kFilterMipLinear) == 0u) level = floor(level + 0.5);
  uint l0 = uint(floor(level));
  float blend = level - float(l0);
  uint first = t.size.w;
  uint w = t.size.x;
  uint h = t.size.y;
  for (uint k = 0u; k < l0; ++k) {
    first += texture_level_words(w, h, t.format.x);
    w = max(w >> 1u, 1u);
    h = max(h >> 1u, 1u);
  }
  vec4 c = texture_sample_level(t, first, w, h, uv, linear);
  if (blend > 0.0 && l0 + 1u < levels) {
    uint first1 = first + texture_level_words(w, h, t.format.x);
    vec4 c1 = texture_sample_level(t, first1, max(w >> 1u, 1u), max(h >> 1u, 1u), uv, linear);
    c = mix(c, c1, blend);
  }
  return c;
}

// The same for record `index` of the scene's texture records.
vec4 texture_sample(uint index, vec2 uv, float lod) {
  return texture_sample_record(scene_textures.t[index], uv, lod);
}

#endif
