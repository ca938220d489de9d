// The G-buffer the raster pass `gbuffer` writes and every later pass reads (restir.*, baseline,
// reference, debug views). One owner for its formats, encodings and conventions:
//
//   image                      format               contents
//   gbuffer.position           R32G32B32A32_SFLOAT  xyz world position; w linear view depth
//                                                   (> 0), 0 where no geometry (sky)
//   gbuffer.normal             R32G32B32A32_SFLOAT  xy octahedral shading normal, zw octahedral
//                                                   geometric normal; both face the camera
//   gbuffer.albedo_roughness   R16G16B16A16_SFLOAT  rgb base colour (linear); a perceptual
//                                                   roughness
//   gbuffer.emission_metallic  R32G32B32A32_SFLOAT  rgb emitted radiance towards the camera
//                                                   (front faces only, 0 otherwise); a metallic
//                                                   (float: radiance spans 1e-8..1e8)
//   gbuffer.ids                R32G32B32A32_UINT    x instance (kNoInstance = sky), y material,
//                                                   z primitive, w 0
//   gbuffer.motion             R32G32B32A32_SFLOAT  motion in pixels, previous pixel position
//                                                   minus current (prev = cur + motion). With a
//                                                   sample jitter (FrameConstants.jitter) pixel
//                                                   p samples the image at p + 0.5 + j.
//                                                   xy: to the previous frame's pixel whose
//                                                   sample was nearest (the point's previous
//                                                   position minus last frame's jitter, minus
//                                                   p + 0.5): what reprojects per-sample
//                                                   history (restir.temporal, denoise.temporal).
//                                                   zw: the point's own motion on screen, without
//                                                   the jitter (xy + last jitter - this one):
//                                                   what moves an unjittered output history
//                                                   (upscale.temporal). Sky: 0 in both
//   gbuffer.depth              D32_SFLOAT           raster depth (not read by compute passes)
//
// Compute passes read the colour images as storage images (imageLoad, layout GENERAL).
#ifndef LANTERN_SHARED_GBUFFER_H
#define LANTERN_SHARED_GBUFFER_H

#include "shared/common_math.h"
#include "shared/lang.h"

LANTERN_BEGIN_SHARED

// Octahedral encoding of a unit vector into [-1, 1]^2 (Cigolle et al. 2014), and back.
LANTERN_FUNC vec2 oct_encode(vec3 n) {
  float l1 = abs(n.x) + abs(n.y) + abs(n.z);
  vec2 p = vec2(n.x, n.y) * (1.0f / (l1 > 0.0f ? l1 : 1.0f));
  if (n.z < 0.0f) {
    float sx = p.x >= 0.0f ? 1.0f : -1.0f;
    float sy = p.y >= 0.0f ? 1.0f : -1.0f;
    p = vec2((1.0f - abs(p.y)) * sx, (1.0f - abs(p.x)) * sy);
  }
  return p;
}

LANTERN_FUNC vec3 oct_decode(vec2 e) {
  vec3 n = vec3(e.x, e.y, 1.0f - abs(e.x) - abs(e.y));
  float t = n.z < 0.0f ? -n.z : 0.0f;
  n.x += n.x >= 0.0f ? -t : t;
  n.y += n.y >= 0.0f ? -t : t;
  return normalize(n);
}

// A unit vector in 32 bits: its octahedral encoding as snorm 2x16 (RestirSurface's normals, the
// similarity key's, the denoiser's guide), and back.
LANTERN_FUNC uint oct_pack_snorm(vec3 n) { return packSnorm2x16(oct_encode(n)); }
LANTERN_FUNC vec3 oct_unpack_snorm(uint packed) { return oct_decode(unpackSnorm2x16(packed)); }

// A clip position moved so the raster's pixel centres sample the image at centre + jitter
// (pixels; FrameConstants.jitter.xy): the geometry shifts by -jitter on screen.
LANTERN_FUNC vec4 gbuffer_jitter_clip(vec4 clip, vec2 jitter, vec2 size) {
  return vec4(clip.x - 2.0f * jitter.x / size.x * clip.w, clip.y - 2.0f * jitter.y / size.y * clip.w,
              clip.z, clip.w);
}

// The camera ray through image point `point` (pixels from the top-left of a `size` image; pixel
// p's raster sample is p + 0.5 + jitter): it starts on the near plane (`origin`) and the returned
// direction reaches the point at NDC depth 0.5, the direction gbuffer.resolve meets triangles with
// (from the camera position, on the same line). What the raster can see along it lies at t in
// [0, far_t]: far_t is where it meets the far plane (3e38 when the projection has none). The
// host G-buffer (GBufferMethod::Host) traces exactly this segment.
LANTERN_FUNC vec3 gbuffer_camera_ray(mat4 inv_view_proj, vec2 point, vec2 size,
                                     LANTERN_OUT(vec3) origin, LANTERN_OUT(float) far_t) {
  vec2 ndc = point / size * 2.0f - 1.0f;
  vec4 a = inv_view_proj * vec4(ndc.x, ndc.y, 0.0f, 1.0f);
  vec4 b = inv_view_proj * vec4(ndc.x, ndc.y, 0.5f, 1.0f);
  vec4 f = inv_view_proj * vec4(ndc.x, ndc.y, 1.0f, 1.0f);
  origin = vec3(a.x, a.y, a.z) / a.w;
  vec3 direction = vec3(b.x, b.y, b.z) / b.w - origin;
  far_t = 3.0e38f;
  float d2 = dot(direction, direction);
  if (f.w > 0.0f && d2 > 0.0f) {
    float t = dot(vec3(f.x, f.y, f.z) / f.w - origin, direction) / d2;
    if (t > 0.0f && t < 3.0e38f) far_t = t;
  }
  return direction;
}

// Motion written where the surface point lies behind the previous camera (no previous pixel):
// it moves the previous position far off-screen, so temporal passes find no history there.
LANTERN_CONST float kGBufferNoPreviousPixel = -1.0e6f;

// gbuffer.motion of a surface point (xy to last frame's jittered sample, zw the point's own
// motion: see the table above) from its clip position this frame (without the jitter) and last
// frame. Both sides go through the same arithmetic, so a point that did not move (same camera,
// same instance transform) gets exactly 0 in zw, and in xy too without jitter, not the ~1e-4 px
// rounding of re-projecting a hit against its pixel centre: a bilinear history tap of that
// weight carries a lit neighbour's second moment into a black pixel's variance, and the
// denoiser's luminance stop then lets the neighbours in.
LANTERN_FUNC vec4 gbuffer_point_motion(vec4 clip, vec4 prev_clip, vec4 jitter, vec2 size) {
  vec2 current = (vec2(clip.x, clip.y) / clip.w * 0.5f + 0.5f) * size;
  vec2 previous = vec2(kGBufferNoPreviousPixel);
  if (prev_clip.w > 0.0f) {
    previous = (vec2(prev_clip.x, prev_clip.y) / prev_clip.w * 0.5f + 0.5f) * size;
  }
  vec2 sampled = (previous - vec2(jitter.z, jitter.w)) - (current - vec2(jitter.x, jitter.y));
  vec2 own = previous - current;
  if (!(prev_clip.w > 0.0f) || !is_finite(sampled.x) || !is_finite(sampled.y) ||
      !is_finite(own.x) || !is_finite(own.y)) {
    return vec4(kGBufferNoPreviousPixel);
  }
  return vec4(sampled.x, sampled.y, own.x, own.y);
}

// Sky test on gbuffer.position.w.
LANTERN_FUNC bool gbuffer_is_sky(float view_depth) { return !(view_depth > 0.0f); }

LANTERN_END_SHARED

#endif
