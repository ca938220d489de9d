// ReSTIR DI knobs: every one settable by name (`--set KEY=VALUE`, a level's "restir" block, the
// play panel later), grouped into presets. Each field says when to change it. The GPU sees them
// through gpu::RestirPush (shaders/shared/restir.h), filled by RestirIntegrator.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "shared/reservoir_mis.h"
#include "shared/restir.h"
#include "shared/volume_restir.h"

namespace lantern::lighting {

// One value of an enumerated setting (bias_correction, debug_view, temporal_permutation): its
// `--set` name, its constant, and when to choose it. The constants the shaders test have one
// owner, the header under shaders/shared/; these tables only name them. temporal_permutation's
// are host-side (below): the shaders see only kRestirFlagTemporalPermutation.
struct RestirChoice {
  const char* name;
  std::uint32_t value;
  const char* when;  // one sentence: the panel's tooltip, the README's table
};

// bias_correction: the kBiasCorrection* constants (shaders/shared/reservoir_mis.h).
std::span<const RestirChoice> restir_bias_corrections();
// debug_view: the kRestirDebug* constants (shaders/shared/restir.h), in their order.
std::span<const RestirChoice> restir_debug_views();
// temporal_permutation: when restir.temporal permutes its history (RestirSettings).
inline constexpr std::uint32_t kTemporalPermutationOff = 0;
inline constexpr std::uint32_t kTemporalPermutationOn = 1;
inline constexpr std::uint32_t kTemporalPermutationDenoised = 2;  // on where the denoiser reads
std::span<const RestirChoice> restir_temporal_permutations();
// The choice whose value is `value` ("?" when there is none).
const char* choice_name(std::span<const RestirChoice> choices, std::uint32_t value);
// light_spread: "auto", the spread measured at load (RestirSettings::light_spread).
inline constexpr float kLightSpreadAuto = -1.0f;

struct RestirSettings {
  // Light candidates per pixel (by power, through presampled tiles and local light lists where
  // those are on). Raise for many-light scenes with little reuse (fast camera, short history);
  // lower when the initial pass dominates frame time.
  std::uint32_t light_candidates = 8;
  // BSDF-sampled candidates (MIS-combined with light candidates): raise for glossy surfaces near
  // large area lights, where light sampling misses the highlight; each one costs a closest-hit ray.
  std::uint32_t bsdf_candidates = 0;
  // ... only on surfaces at least this glossy (brdf_gloss, shaders/shared/brdf.h: max(metallic,
  // specular x (1 - roughness) / 2): 1 for metals, at most 0.5 for dielectrics), where light
  // sampling misses a highlight; elsewhere none. 0: every surface. A level none of whose
  // materials reaches it traces no BSDF ray at all (RestirIntegrator::bsdf_candidates).
  float bsdf_min_gloss = 0.0f;
  // Reuse last frame's reservoirs along motion vectors. Turn off to see the spatial-only result
  // or when history is worthless (every frame a cut).
  bool temporal = true;
  // Temporal permutation (restir_permuted_history_pixel, shaders/shared/restir.h): temporal
  // reuse takes last frame's reservoir from a neighbour of the reprojected pixel, the direction
  // drawn anew each frame, so a sample (an occluded one, say) no longer sticks to one pixel for
  // up to m_cap frames. Unbiased; the raw image is noisier and flickers more, the denoised one is
  // cleaner (the denoiser averages frames, and their errors are now less alike). `denoised` (the
  // default) turns it on exactly for frames the denoiser consumes (FrameInputs::denoised: play,
  // PNG, video); `on` / `off` force it. One of restir_temporal_permutations().
  std::uint32_t temporal_permutation = kTemporalPermutationDenoised;
  // History confidence cap as a multiple of the current M (light + BSDF candidates). Lower it
  // when lights move or flicker and stale samples linger; raise it for static scenes.
  float m_cap_factor = 20.0f;
  // In frames the denoiser consumes (FrameInputs::denoised), the cap's fraction where a surface
  // point moves a pixel or more on screen, linearly up to the full cap where it holds still
  // (restir_history_m_cap, shared/restir.h). With a moving view a sample then turns over sooner,
  // so consecutive frames' errors differ and the denoiser averages them (night_market walking,
  // 160x90: denoised relMSE 3-19% lower on 7 seeds at 0.25); a still view keeps its long history.
  // Raw frames (EXR, bias studies) always use the full cap. 1 turns it off. Unbiased either way.
  float m_cap_moving = 0.25f;
  // Last frame's final reservoirs that restir.temporal merges besides the reprojected pixel's,
  // drawn within `radius` around it and passing the same disocclusion test (plus
  // disocclusion_boost where the reprojected pixel fails it): spatial reuse from last frame's
  // neighbours in the temporal pass itself (RTXDI's fused spatiotemporal mode), where
  // restir.spatial reuses this frame's in a pass of its own. With spatial_passes 0 it stands in
  // for that pass, saving the pass's fixed part only (on lavapipe a history neighbour costs what
  // a spatial one does: the frame 1.00x at 320x180, 0.94x at 640x360, for noisier images:
  // README); a disocclusion then finds only what last frame saw beside it. 0: the reprojected
  // pixel alone. Unbiased with pairwise or balance MIS. No effect with `temporal` off.
  std::uint32_t temporal_neighbours = 0;
  // One reservoir per reservoir_stride x reservoir_stride pixels: restir.initial, restir.temporal
  // and restir.spatial resample for one representative pixel of each block (a different one
  // each frame), and restir.shade resamples the block's final reservoir again for each of its
  // other pixels with one light candidate of the pixel's own (unbiased: restir_shade.comp's
  // resample_for_pixel). 2 cuts the resampling passes to about a quarter for more noise. 1: one
  // per pixel. Not with visibility_reuse (a verdict is one pixel's).
  std::uint32_t reservoir_stride = 1;
  // Spatial reuse passes. More passes spread good samples further (less noise) at a full pass's
  // cost each; 0 for temporal-only.
  std::uint32_t spatial_passes = 1;
  // Neighbours per spatial pass. More neighbours lower noise at linear (none/pairwise) or
  // quadratic (balance) cost.
  std::uint32_t neighbours = 4;
  // Extra neighbours where a pixel's history is short (just disoccluded): raise when
  // disocclusions stay noisy for several frames. With temporal_neighbours, also the extra
  // history neighbours where the reprojected pixel fails the disocclusion test.
  std::uint32_t disocclusion_boost = 2;
  // Search radius of spatial neighbours in pixels (and of temporal_neighbours around the
  // reprojected pixel). Larger finds more light over flat areas but rejects more neighbours on
  // busy geometry; scale it with resolution.
  float radius = 16.0f;
  // How MIS weights combine reservoirs: none (1/M, fastest, darkens contact shadows), balance
  // (unbiased, O(k^2) target evaluations), pairwise (unbiased, O(k)).
  // One of restir_bias_corrections() (a kBiasCorrection* constant).
  std::uint32_t bias_correction = gpu::kBiasCorrectionPairwise;
  // Light presampling tiles of kRestirPresampleTileSize lights each (shared/restir.h): light
  // candidates are drawn from one tile per 8x8 workgroup instead of the whole list, which keeps
  // their reads in cache. 0 turns it off (the alias table directly: fewer correlated candidates,
  // slower with many lights). More tiles decorrelate neighbouring workgroups at more memory; a
  // level gets at most its light spread rounded up (RestirIntegrator::presample_tiles).
  std::uint32_t presample_tiles = 32;
  // Local light lists (shared/restir.h): draws per slot of each 8x8 tile's 64-slot list, picked
  // by RIS towards lights near the tile's surfaces; the tile's light candidates come from its
  // slots. Raise where small lights sit close to surfaces among many others (lamps, lanterns,
  // strips: far less noise next to them); 0 turns it off (candidates by power alone, cheaper per
  // candidate on scenes where every light is far or alike). Used only where the level has at
  // least local_min_lights lights and a light spread of at least 16
  // (RestirIntegrator::local_candidates).
  std::uint32_t local_candidates = 8;
  // Light candidates drawn near the pixel's own surface point from the light grid
  // (shared/light_grid.h: one of the 27 cells around it, one of that cell's lights), besides
  // light_candidates; combined with them and the BSDF candidates by the balance heuristic, so a
  // light beside the surface (a lantern beside a stall's roof, which the power draws and the
  // local lists find once in tens of frames and then weigh 100x) is drawn at its own density
  // every frame. Used where the local lists are (RestirIntegrator::grid_candidates). 0 turns
  // them off.
  std::uint32_t grid_candidates = 2;
  // The light count from which the local lists are used: by default more than one presampling
  // tile. Below it RIS over the power distribution already finds every light (cornell_lights' 89
  // emitters: the lists changed its raw relMSE by 0.96-2.1x); lower it for a level of a few
  // hundred lights spread far apart.
  std::uint32_t local_min_lights = gpu::kRestirPresampleTileSize + 1;
  // The level's light spread as the presampling tiles and local lists see it
  // (RestirIntegrator::presample_tiles, local_candidates): kLightSpreadAuto takes the one measured
  // at load (SceneData::light_spread, `lantern info`'s light_sampling.spread); a value >= 0 states
  // it (e.g. 1000: lights that each light only their surroundings, whatever was measured).
  float light_spread = kLightSpreadAuto;
  // Visibility reuse: a sample the pixel's history found unoccluded is shaded without a shadow
  // ray, and tested again every this many frames (staggered over pixels). 0 is off (one shadow
  // ray per pixel, unbiased). Exact for a still camera over still geometry; where the camera or
  // occluders move, shadows lag by up to this many frames. Off in every preset: on night_market
  // 320x180 (flythrough) 4 cut restir.shade to 0.83x only, since samples taken from spatial
  // neighbours must be tested and nearly every 8-lane batch holds one.
  std::uint32_t visibility_reuse = 0;
  // Shadow-test the initial pick and drop it when occluded: fewer occluded samples spread by
  // reuse (much less noise in shadowed areas), one more ray per pixel, slight darkening bias.
  bool initial_visibility = false;
  // Boiling filter 0..1: drops reservoirs far above their tile's mean weight (the bright
  // "boiling" blobs long histories make). 0 is off (unbiased); raise to 0.2-0.5 if blobs appear.
  float boiling_filter = 0.0f;
  // Disocclusion / neighbour similarity: relative view-depth difference allowed. Lower on thin
  // geometry that leaks; raise when reuse is rejected on steep surfaces.
  float depth_threshold = 0.1f;
  // Minimum cosine between normals for reuse (0.9 = 25 degrees). Lower on bumpy surfaces.
  float normal_threshold = 0.9f;
  // What hdr shows: radiance, or one of restir_debug_views() (a kRestirDebug* constant).
  std::uint32_t debug_view = gpu::kRestirDebugNone;

  // Media reservoirs (levels with volumes; lighting/volume/volume_restir.h). The knobs of the
  // in-scattering along camera rays, apart from the surfaces'.
  struct Volume {
    // (medium, distance, light) candidates per pixel. Raise where fog around many lights stays
    // noisy; each costs a density lookup and a light evaluation (no ray).
    std::uint32_t candidates = 8;
    // Reuse last frame's media reservoirs at the reprojected scattering point.
    bool temporal = true;
    // History confidence cap as a multiple of `candidates`: lower when media or lights move.
    float m_cap_factor = 20.0f;
    // Spatial neighbours (0: none). Their MIS weights follow bias_correction: linear cost for
    // pairwise, quadratic for balance.
    std::uint32_t neighbours = 3;
    // Spatial disk radius in pixels.
    float radius = 12.0f;
    float m_cap() const { return m_cap_factor * static_cast<float>(candidates); }
  } volume;

  // Current M: candidates drawn per pixel per frame (at most: bsdf_min_gloss may leave a pixel,
  // or a whole level, without its BSDF candidates), before the light grid candidates, which a
  // frame adds where RestirIntegrator::grid_candidates draws them (make_push's cap counts them).
  std::uint32_t candidates() const { return light_candidates + bsdf_candidates; }
  float m_cap() const { return m_cap(candidates()); }
  // The cap for a frame that draws `drawn` candidates per pixel.
  float m_cap(std::uint32_t drawn) const { return m_cap_factor * static_cast<float>(drawn); }
};

// "fast" | "balanced" | "quality"; lantern::InputError naming the value otherwise.
RestirSettings restir_preset(std::string_view name);
std::vector<std::string> restir_preset_names();

// Sets one knob by its key (the field names above: light_candidates, bsdf_candidates,
// bsdf_min_gloss, temporal, m_cap (alias of m_cap_factor), m_cap_moving, reservoir_stride,
// spatial_passes, neighbours, disocclusion_boost, temporal_neighbours, radius, presample_tiles,
// local_candidates, grid_candidates, local_min_lights, visibility_reuse, bias_correction (a
// name from restir_bias_corrections()), initial_visibility, boiling_filter, depth_threshold,
// normal_threshold, debug_view (a name from restir_debug_views()), temporal_permutation (a name
// from restir_temporal_permutations()); the media's volume_candidates, volume_temporal,
// volume_m_cap, volume_neighbours, volume_radius).
// lantern::InputError naming the key and the value for unknown keys, unparsable values and
// values outside the allowed range (e.g. light_candidates = 0 or 10^9).
void apply_setting(RestirSettings& settings, std::string_view key, std::string_view value);

// Presets then settings in order: what --preset P --set K=V ... means. lantern::InputError for
// settings that exclude each other (visibility_reuse with reservoir_stride > 1).
RestirSettings make_restir_settings(
    std::string_view preset, const std::vector<std::pair<std::string, std::string>>& settings);

// Every key with its current value ("key=value" lines), for logs and bench JSON.
std::vector<std::pair<std::string, std::string>> describe(const RestirSettings& settings);

}  // namespace lantern::lighting
