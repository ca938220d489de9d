// ReSTIR DI constants and records shared by lighting/restir/*.cpp and shaders/restir/*.comp: the
// push constants every restir.* pass receives, the compact per-pixel surface record the passes
// resample with (and the temporal pass keeps as history), debug views and flags. The knobs behind
// the push constants, with when to change each, are lighting/restir/restir_settings.h.
#ifndef LANTERN_SHARED_RESTIR_H
#define LANTERN_SHARED_RESTIR_H

#include "shared/common_math.h"
#include "shared/gbuffer.h"
#include "shared/lang.h"
#include "shared/lights.h"
#include "shared/rng.h"

LANTERN_BEGIN_SHARED

// Upper bounds the shaders size their loops and arrays by (settings are validated against them).
LANTERN_CONST uint kRestirMaxLightCandidates = 256u;
LANTERN_CONST uint kRestirMaxBsdfCandidates = 16u;
LANTERN_CONST uint kRestirMaxNeighbours = 8u;   // spatial neighbours per pass, boost included
                                                // (and restir.temporal's history neighbours)
LANTERN_CONST uint kRestirMaxReservoirStride = 4u;  // RestirSettings::reservoir_stride
LANTERN_CONST uint kRestirMaxSpatialPasses = 4u;
LANTERN_CONST uint kRestirTemporalTries = 4u;   // reprojected pixel, then 3 jittered retries

// RestirPush.flags bits.
LANTERN_CONST uint kRestirFlagHistoryValid = 1u;       // last frame's reservoirs may be reused
LANTERN_CONST uint kRestirFlagInitialVisibility = 2u;  // shadow-test the initial pick
// restir.temporal reads last frame's reservoir at a neighbour of the reprojected pixel
// (restir_permuted_history_pixel) instead of the pixel itself.
LANTERN_CONST uint kRestirFlagTemporalPermutation = 4u;

// Debug views (`debug_view` setting): written into hdr instead of radiance.
LANTERN_CONST uint kRestirDebugNone = 0u;
LANTERN_CONST uint kRestirDebugW = 1u;             // W (grey, log-ish: W / (1 + W))
LANTERN_CONST uint kRestirDebugM = 2u;             // M / M cap
LANTERN_CONST uint kRestirDebugAge = 3u;           // sample age / 32 frames
LANTERN_CONST uint kRestirDebugLight = 4u;         // hashed colour of the selected light
LANTERN_CONST uint kRestirDebugDisocclusion = 5u;  // red: no history, green: reprojected, yellow: retry
LANTERN_CONST uint kRestirDebugMotion = 6u;        // motion vector, 0.5 + motion / 16 px in r, g
LANTERN_CONST uint kRestirDebugCount = 7u;

// restir.temporal's per-pixel status (buffer of uint, read by the disocclusion view).
LANTERN_CONST uint kRestirStatusNoHistory = 0u;
LANTERN_CONST uint kRestirStatusReprojected = 1u;  // 1 + retry index when a retry matched

// RNG streams (rng_init's `pass`) of the restir passes.
LANTERN_CONST uint kRestirRngInitial = 0x52490u;
LANTERN_CONST uint kRestirRngTemporal = 0x52491u;
LANTERN_CONST uint kRestirRngSpatial = 0x52492u;  // + pass index
LANTERN_CONST uint kRestirRngPresample = 0x524a0u;
LANTERN_CONST uint kRestirRngPresampleTile = 0x524a1u;
LANTERN_CONST uint kRestirRngLocalLights = 0x524a2u;
LANTERN_CONST uint kRestirRngInitialBsdf = 0x524a3u;  // restir.initial's BSDF candidates
LANTERN_CONST uint kRestirRngInitialGrid = 0x524a4u;  // restir.initial's light grid candidates
LANTERN_CONST uint kRestirRngShadeMedia = 0x524b0u;  // restir.shade's transmittance estimate
LANTERN_CONST uint kRestirRngShadeCanonical = 0x524b1u;  // restir.shade's own candidate
LANTERN_CONST uint kRestirRngTemporalPermutation = 0x524c0u;  // one draw per frame, every pixel's

// Temporal permutation (kRestirFlagTemporalPermutation): the previous pixel restir.temporal first
// tries for reprojected pixel q, given one random word `frame_bits` per frame (the same for every
// pixel). The grid is shifted by 0 or 1 pixel per axis and each coordinate XORed with 1 where the
// mask (one of (1,0), (0,1), (1,1)) says: a bijection of the pixel grid onto itself that moves
// every pixel by one pixel horizontally, vertically or diagonally, the way drawn anew each frame.
// Being a permutation, each history reservoir still seeds exactly one pixel (no reservoir is
// copied twice, which would correlate neighbours); moving, a pixel no longer inherits its own
// history frame after frame, so a sample (an occluded one, say) no longer sticks to one pixel
// for up to m_cap frames: the temporal correlation a denoiser cannot average away. The history
// surface is a neighbour's, which the MIS weights see (as for a jittered retry), so the estimate
// stays unbiased; the raw image is noisier next to sharp changes in the target (lights close to
// a surface).
// The frame's word: one draw of the frame's kRestirRngTemporalPermutation stream (the host
// computes it once per frame, RestirPush.permutation_bits).
LANTERN_FUNC uint restir_permutation_bits(uint frame_index, uint seed) {
  uint state = rng_init(uvec2(0u, 0u), frame_index, seed, kRestirRngTemporalPermutation);
  return rng_next_uint(state);
}

LANTERN_FUNC ivec2 restir_permuted_history_pixel(ivec2 q, uint frame_bits) {
  int shift_x = int(frame_bits & 1u);
  int shift_y = int((frame_bits >> 1u) & 1u);
  uint mask = 1u + (frame_bits >> 2u) % 3u;  // 1, 2 or 3: x, y or both
  int flip_x = int(mask & 1u);
  int flip_y = int(mask >> 1u);
  return ivec2(((q.x + shift_x) ^ flip_x) - shift_x, ((q.y + shift_y) ^ flip_y) - shift_y);
}

// The M cap restir.temporal applies to a pixel's history: m_cap where the surface point holds
// still on screen, m_cap x moving_fraction where it moves a pixel or more (own_motion: the
// G-buffer motion's zw, the point's own motion in pixels, without the jitter step; non-finite
// counts as moving), linearly between. With a moving view a sample then turns over sooner, so
// consecutive frames' errors differ and a denoiser's temporal accumulation averages them
// (RestirPush.m_cap_moving: the settings' m_cap_moving in frames the denoiser consumes, else 1).
// Any cap keeps the MIS weights a partition of unity: unbiased.
LANTERN_FUNC float restir_history_m_cap(float m_cap, float moving_fraction, vec2 own_motion) {
  float moving = 1.0f;
  if (is_finite(own_motion.x) && is_finite(own_motion.y)) {
    moving = clamp(length(own_motion), 0.0f, 1.0f);
  }
  return m_cap * (1.0f + (moving_fraction - 1.0f) * moving);
}

// Light presampling (RIS tiles, Wyman and Panteleev, HPG 2021): restir.presample draws
// kRestirPresampleTileSize lights per tile from the power alias table into push.presample_tiles
// tiles, each entry a copy of the light record with its density; restir.initial then draws one
// workgroup's light candidates uniformly from one tile, so its reads stay within the tile's
// 80 KiB instead of the whole light list (night_market: 8 MiB of light records read at random).
// Every candidate keeps the alias table's marginal distribution, so RIS stays unbiased; the
// candidates of one tile are correlated, which costs a little variance.
LANTERN_CONST uint kRestirPresampleTileSize = 1024u;
LANTERN_CONST uint kRestirMaxPresampleTiles = 1024u;

// Local light lists (push.local_candidates = N > 0): in restir.initial every invocation of an 8x8
// workgroup first fills one slot of the workgroup's list (shared memory) by RIS over N
// light-strategy draws (the presampled tile, else the alias table) with target
// pdf(l) / max(d^2, r^2): d the distance from its own pixel's surface point to the light's first vertex or position
// (one scene radius for a directional light), r = kRestirLocalMinDistance x the scene radius; a sky
// pixel's slot uses pdf(l) alone. The workgroup's light candidates are then drawn uniformly from
// its 64 slots, each with the slot's unbiased contribution weight in place of 1 / pdf. The target
// is positive for every light, so every slot covers every light and RIS stays unbiased; what
// changes is that lights near the tile are drawn far more often than their share of the power.
// (night_market: a stall wall 0.27 m from one of 5760 lanterns read 14,812 against a reference of
// 70 on the frame a candidate found that lantern, and about 0 on the others.) MIS with BSDF
// candidates keeps the light strategy's own density as its weight (any weights that sum to one keep
// RIS unbiased).
LANTERN_CONST float kRestirLocalMinDistance = 0.005f;
LANTERN_CONST uint kRestirMaxLocalCandidates = 256u;

struct PresampledLight {
  GpuLight light;  // a copy of scene_light(index) (this frame's)
  uint index;      // the light's index in the list
  float pdf;       // alias selection pdf x point density (light_eval_point_pdf): area measure
  uvec2 grid_cell;  // the light's light_cells record (shared/light_grid.h): cell key, share
};
LANTERN_STATIC_SIZE(PresampledLight, 80);
// rgba32ui texels per PresampledLight through restir.initial's texel view: the light's
// kGpuLightTexels, then (index, pdf, grid_cell.x, grid_cell.y).
LANTERN_CONST uint kPresampledLightTexels = 5u;

// What the restir.* passes take from the settings (lighting/restir/restir_settings.h). The frame's
// size, index, seed, light counts and scene radius are FrameConstants' (restir_common.glsl).
struct RestirPush {
  uint tile_stride;       // without tile_bands, workgroup g handles tile (g * tile_stride) mod
                          // tile count (coprime)
  uint flags;             // kRestirFlag*
  uint light_candidates;  // initial candidates from light sampling
  uint bsdf_candidates;   // initial candidates from BSDF rays
  uint bias_correction;   // kBiasCorrection* (shared/reservoir_mis.h)
  uint debug_view;        // kRestirDebug*
  uint neighbours;        // spatial neighbours per pass
  uint spatial_pass;      // this spatial pass's index (seeds its random numbers)
  uint boost_neighbours;  // extra spatial neighbours for a pixel short of history
  uint short_history_m;   // M below which a pixel counts as short of history
  float radius;           // spatial radius in pixels
  float m_cap;            // temporal M cap (absolute)
  float boiling_filter;   // boiling filter strength 0..1
  uint presample_tiles;   // light presampling tiles (0: draws from the alias table directly)
  uint visibility_reuse;  // re-test a reused visible sample every this many frames (0: off)
  uint tile_bands;        // > 0: workgroups walk interleaved bands of tile rows (CPU devices)
  vec4 similarity;        // restir_surfaces_similar's thresholds: x max relative depth difference;
                          // y min cos between normals; z max roughness difference; w unused
  uint local_candidates;  // > 0: draws per slot of restir.initial's local light lists (0: off)
  uint permutation_bits;  // with kRestirFlagTemporalPermutation: this frame's word for
                          // restir_permuted_history_pixel (restir_permutation_bits)
  float m_cap_moving;     // m_cap's fraction where a point moves a pixel or more
                          // (restir_history_m_cap; 1: the same cap everywhere)
  float bsdf_min_gloss;   // BSDF candidates only where brdf_gloss (shared/brdf.h) reaches this
  uint temporal_neighbours;  // restir.temporal's neighbours from last frame around the
                             // reprojected pixel (0: the reprojected pixel alone)
  uint reservoir_stride;     // one reservoir per stride x stride pixels (restir_grid_size); 1:
                             // one per pixel
  uint representative;       // this frame's offset of the pixel each reservoir resamples for,
                             // inside its stride x stride block: x | y << 16
                             // (restir_representative)
  uint grid_candidates;      // restir.initial's candidates from the light grid near the pixel
};
LANTERN_STATIC_SIZE(RestirPush, 112);

// The reservoir grid of an image of `size` pixels: one cell per stride x stride pixels, the last
// column and row of cells holding what is left (RestirPush::reservoir_stride).
LANTERN_FUNC uvec2 restir_grid_extent(uvec2 size, uint stride) {
  uint s = max(stride, 1u);
  return (size + s - 1u) / s;
}

// The per-pixel surface the passes resample at, packed from the G-buffer by restir.initial
// (and kept one frame as history for restir.temporal's disocclusion test). 48 bytes: albedo,
// roughness, metallic and specular are unorm16 (error <= 7.6e-6), so ReSTIR shades the G-buffer's
// material to within 1e-5 relative, as the baseline does (with unorm8 an albedo of 0.5 read as
// 128/255, 0.4% too bright; restir.* frame times with 48 against 32 bytes: README).
struct RestirSurface {
  vec4 position_depth;  // xyz world position; w linear view depth (0: sky, no surface)
  uvec4 packed;         // x: oct shading normal (snorm 2x16); y: oct geometric normal;
                        // z: albedo r, g (unorm 2x16); w: albedo b, roughness (unorm 2x16)
  uvec4 material;       // x: metallic, specular factor (unorm 2x16); y: material id; z, w: 0
};
LANTERN_STATIC_SIZE(RestirSurface, 48);
// rgba32ui texels per RestirSurface where a pass reads surfaces through a texel view
// (restir_surface_fetch): position_depth, packed, material.
LANTERN_CONST uint kRestirSurfaceTexels = 3u;

LANTERN_FUNC RestirSurface restir_surface_sky() {
  RestirSurface s;
  s.position_depth = vec4(0.0f);
  s.packed = uvec4(0u);
  s.material = uvec4(0u);
  return s;
}

LANTERN_FUNC RestirSurface restir_surface_pack(vec4 position_depth, vec3 n, vec3 ng, vec3 albedo,
                                               float roughness, float metallic, float specular,
                                               uint material) {
  RestirSurface s;
  bool finite = is_finite(position_depth.x) && is_finite(position_depth.y) &&
                is_finite(position_depth.z) && is_finite(position_depth.w);
  if (!finite || gbuffer_is_sky(position_depth.w)) {
    return restir_surface_sky();
  }
  vec3 a = clamp(albedo, vec3(0.0f), vec3(1.0f));
  s.position_depth = position_depth;
  s.packed.x = oct_pack_snorm(n);
  s.packed.y = oct_pack_snorm(ng);
  s.packed.z = packUnorm2x16(vec2(a.x, a.y));
  s.packed.w = packUnorm2x16(vec2(a.z, clamp(roughness, 0.0f, 1.0f)));
  s.material.x = packUnorm2x16(vec2(clamp(metallic, 0.0f, 1.0f), clamp(specular, 0.0f, 1.0f)));
  s.material.y = material;
  s.material.z = 0u;
  s.material.w = 0u;
  return s;
}

LANTERN_FUNC bool restir_surface_valid(RestirSurface s) { return !gbuffer_is_sky(s.position_depth.w); }
LANTERN_FUNC vec3 restir_surface_position(RestirSurface s) { return vec3(s.position_depth); }
LANTERN_FUNC float restir_surface_depth(RestirSurface s) { return s.position_depth.w; }
LANTERN_FUNC vec3 restir_surface_normal(RestirSurface s) { return oct_unpack_snorm(s.packed.x); }
LANTERN_FUNC vec3 restir_surface_geometric_normal(RestirSurface s) {
  return oct_unpack_snorm(s.packed.y);
}
LANTERN_FUNC vec3 restir_surface_albedo(RestirSurface s) {
  vec2 rg = unpackUnorm2x16(s.packed.z);
  return vec3(rg.x, rg.y, unpackUnorm2x16(s.packed.w).x);
}
LANTERN_FUNC float restir_surface_roughness(RestirSurface s) { return unpackUnorm2x16(s.packed.w).y; }
LANTERN_FUNC float restir_surface_metallic(RestirSurface s) { return unpackUnorm2x16(s.material.x).x; }
LANTERN_FUNC float restir_surface_specular(RestirSurface s) { return unpackUnorm2x16(s.material.x).y; }
LANTERN_FUNC uint restir_surface_material(RestirSurface s) { return s.material.y; }

// What the reuse test (restir_surfaces_similar) reads of a surface, 16 bytes: a pass that keeps a
// surface only to test reuse against it later (the denoiser's history) keeps this instead of the
// 48-byte RestirSurface. Values exactly as the surface's accessors return them.
struct RestirSimilarityKey {
  float depth;      // linear view depth (0: sky, no surface)
  uint normal;      // shading normal, oct snorm 2x16 (RestirSurface.packed.x)
  uint material;    // material id
  float roughness;  // unorm16-quantised, as restir_surface_roughness
};
LANTERN_STATIC_SIZE(RestirSimilarityKey, 16);

LANTERN_FUNC RestirSimilarityKey restir_similarity_key(RestirSurface s) {
  RestirSimilarityKey k;
  k.depth = restir_surface_depth(s);
  k.normal = s.packed.x;
  k.material = restir_surface_material(s);
  k.roughness = restir_surface_roughness(s);
  return k;
}

// Whether a surface with key `other` is close enough to one with key `s` to reuse its
// reservoir (or, in the denoiser, its history): both are surfaces, the view depth differs by at
// most similarity.x relative (`expected_depth` is s's depth as `other`'s camera saw it: its own
// depth for spatial neighbours, its reprojected depth for history), normals within
// acos(similarity.y), same material id and roughness within similarity.z.
LANTERN_FUNC bool restir_keys_similar(RestirSimilarityKey s, float expected_depth,
                                      RestirSimilarityKey other, vec4 similarity) {
  if (gbuffer_is_sky(s.depth) || gbuffer_is_sky(other.depth)) {
    return false;
  }
  float d_other = other.depth;
  if (!(abs(expected_depth - d_other) <= similarity.x * max(expected_depth, d_other))) {
    return false;
  }
  if (dot(oct_unpack_snorm(s.normal), oct_unpack_snorm(other.normal)) < similarity.y) {
    return false;
  }
  if (s.material != other.material) {
    return false;
  }
  return abs(s.roughness - other.roughness) <= similarity.z;
}

// The same test on two surfaces.
LANTERN_FUNC bool restir_surfaces_similar(RestirSurface s, float expected_depth,
                                          RestirSurface other, vec4 similarity) {
  return restir_keys_similar(restir_similarity_key(s), expected_depth,
                             restir_similarity_key(other), similarity);
}

LANTERN_END_SHARED

#endif
