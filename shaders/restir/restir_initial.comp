// restir.initial: per cell of the reservoir grid (a pixel, or with push.reservoir_stride > 1 a
// block's representative, restir_representative, whose block's surfaces it also packs into
// pixel_surfaces), packs the G-buffer into a RestirSurface and resamples
// push.light_candidates light candidates (the environment map with its selection probability,
// else a light by power, or through the local light list, x uniform point on the light) plus
// push.grid_candidates light grid candidates (a light near the pixel's surface point:
// scene_light_grid_draw) and push.bsdf_candidates BSDF candidates where the surface is at least
// push.bsdf_min_gloss glossy (bsdf_candidates_at; a closest-hit ray each: an emissive triangle
// hit, or the environment when the ray escapes, is a candidate), combined by the balance
// heuristic over the strategies, with target p̂ = luminance of the unshadowed contribution.
// Light candidates come from this workgroup's tile of presampled lights when
// push.presample_tiles > 0 (restir.presample), and through the workgroup's local light list when
// push.local_candidates > 0 (shared/restir.h: every invocation first fills one slot, by RIS
// towards lights near its own surface point). Optionally shadow-tests the pick
// (kRestirFlagInitialVisibility).
// Reads: gbuffer position/normal/albedo_roughness/emission_metallic/ids, scene materials,
// instances, lights, alias table, light grid and light_cells (grid candidates), environment
// (env_*), BVH (BSDF candidates, visibility), presampled_lights (restir.presample's; a stand-in
// when presampling is off).
// Writes: restir_surfaces (history resource "restir.surfaces"), reservoirs_out, pixel_surfaces
// (push.reservoir_stride > 1). History: none.
// Dispatch: one workgroup per 8x8 tile on every device (its local light list is the tile's:
// lighting/restir/restir_pass.cpp), shuffled (push.tile_stride).
// Host closest hits (shared/host_visibility.h, with the host visibility backend and BSDF
// candidates): the "closestemit" variant (restir.initial_rays) writes each pixel's BSDF
// candidate rays into the host's closest-hit ray buffer and nothing else; visibility.host_closest
// traces them; the "closestresolve" variant (restir.initial) reads their hits instead of
// tracing. Both draw the BSDF candidates from their own stream (kRestirRngInitialBsdf).
#version 460
#extension GL_GOOGLE_include_directive : require

// The scene (BVH through rgba32ui texel views: 1.24x faster restir.shade than storage buffers on
// night_market) comes from lib/scene_buffers.glsl through restir_common.glsl.
#include "restir/restir_common.glsl"
#include "shared/alias_table.h"
#include "shared/brdf.h"
#include "shared/sampling.h"

layout(binding = PASS_BINDING(0), rgba32f) readonly uniform image2D gbuffer_position;
layout(binding = PASS_BINDING(1), rgba32f) readonly uniform image2D gbuffer_normal;
layout(binding = PASS_BINDING(2), rgba16f) readonly uniform image2D gbuffer_albedo_roughness;
layout(binding = PASS_BINDING(3), rgba32f) readonly uniform image2D gbuffer_emission_metallic;
layout(binding = PASS_BINDING(4), rgba32ui) readonly uniform uimage2D gbuffer_ids;
layout(std430, binding = PASS_BINDING(5)) writeonly buffer SurfaceOut {
  RestirSurface s[];
} restir_surfaces;
layout(std430, binding = PASS_BINDING(6)) writeonly buffer ReservoirOut {
  PackedReservoir r[];
} reservoirs_out;
layout(binding = PASS_BINDING(7)) uniform utextureBuffer presampled_lights;
// With push.reservoir_stride > 1: every pixel's surface (restir.shade's); restir_surfaces then
// holds each cell's representative's.
layout(std430, binding = PASS_BINDING(8)) writeonly buffer PixelSurfaceOut {
  RestirSurface s[];
} pixel_surfaces;

// Probability of the GGX lobe in the BSDF sampling mixture (the rest is cosine-weighted).
float specular_lobe_probability(ShadingPoint p) {
  return brdf_gloss(p.roughness, p.metallic, p.specular);
}

// BSDF candidates at p: push.bsdf_candidates on surfaces at least push.bsdf_min_gloss glossy,
// none elsewhere. Each pixel's MIS weighs the strategies it drew, so either way its initial
// reservoir is unbiased. The one decision the "closestemit" variant and restir.initial share.
uint bsdf_candidates_at(ShadingPoint p) {
  return specular_lobe_probability(p) >= push.bsdf_min_gloss ? push.bsdf_candidates : 0u;
}

float bsdf_direction_pdf(ShadingPoint p, vec3 l) {
  float ps = specular_lobe_probability(p);
  return ps * ggx_vndf_pdf(p.n, p.v, l, p.roughness) + (1.0 - ps) * cosine_hemisphere_pdf(p.n, l);
}

// BSDF strategy density of light point y (area measure) seen from p: solid-angle pdf * G.
float bsdf_area_pdf(ShadingPoint p, GpuLight light, vec3 y) {
  if (light_kind(light) != kLightTriangle) return 0.0;
  vec3 to_light = y - p.x;
  float dist2 = dot(to_light, to_light);
  if (!(dist2 > 0.0)) return 0.0;
  vec3 l = to_light * inversesqrt(dist2);
  float geometry = light_eval_triangle_geometry(light, l, dist2);
  return geometry > 0.0 ? bsdf_direction_pdf(p, l) * geometry : 0.0;
}

// restir.initial's local light list (shared/restir.h, push.local_candidates > 0): per slot, the
// presampled entry (or, without presampling, the light index) it holds, the slot's effective
// density (1 / its unbiased contribution weight, area measure like pdf) and the light strategy's
// own density of that light (MIS with BSDF candidates).
const uint kLocalSlots = kPixelGroupThreads;
shared uint local_entry[kLocalSlots];
shared float local_pdf[kLocalSlots];
shared float local_strategy_pdf[kLocalSlots];

// One light-strategy draw from u0, u1 (in [0,1)): an entry of this workgroup's presampled tile
// when presampling is on, else a light index from the alias table.
uint draw_strategy_entry(float u0, float u1, uint tile_base) {
  if (push.presample_tiles > 0u) {
    uint slot = min(uint(u0 * float(kRestirPresampleTileSize)), kRestirPresampleTileSize - 1u);
    return tile_base + slot;
  }
  return scene_light_sample(u0, u1);
}

// A draw_strategy_entry result's light index, record and density (selection pdf x point density),
// and with presampling its light grid record (else (kLightGridNoCell, 0): light_cells holds it).
uint strategy_entry_light(uint entry, out GpuLight light, out float pdf, out uvec2 grid_cell) {
  if (push.presample_tiles > 0u) {
    // PresampledLight through its texel view: the light record, then index, pdf and grid record.
    uint base = kPresampledLightTexels * entry;
    light = gpu_light_fetch(presampled_lights, base);
    uvec4 index_pdf_cell = texelFetch(presampled_lights, int(base + kGpuLightTexels));
    pdf = uintBitsToFloat(index_pdf_cell.y);
    grid_cell = index_pdf_cell.zw;
    return index_pdf_cell.x;
  }
  light = scene_light(entry);
  pdf = scene_light_selection_pdf(entry) * light_eval_point_pdf(light);
  grid_cell = uvec2(kLightGridNoCell, 0u);
  return entry;
}

// The same entry's first vertex or position (p0) and density, without the rest of the record
// unless the density needs it (a triangle from the alias table): what a local slot's draws read.
vec4 strategy_entry_position(uint entry, out float pdf) {
  if (push.presample_tiles > 0u) {
    uint base = kPresampledLightTexels * entry;
    pdf = uintBitsToFloat(texelFetch(presampled_lights, int(base + kGpuLightTexels)).y);
    return uintBitsToFloat(texelFetch(presampled_lights, int(base)));
  }
  vec4 p0 = uintBitsToFloat(texelFetch(scene_light_texels, int(kGpuLightTexels * entry)));
  pdf = scene_light_selection_pdf(entry) *
        (floatBitsToUint(p0.w) == kLightTriangle ? light_eval_point_pdf(scene_light(entry)) : 1.0);
  return p0;
}

// Fills this invocation's slot of the local light list: RIS over push.local_candidates draws
// with target pdf(l) x g(l), g = 1 / max(d^2, r^2), d from x to the light's first vertex or
// position (a directional light counts as one scene radius away; without a surface point g = 1).
// The slot keeps the pick with density pdf x g x N / sum(g).
void fill_local_slot(uvec2 cell, bool has_point, vec3 x, uint tile_base) {
  uint slot = gl_LocalInvocationIndex;
  local_entry[slot] = 0u;
  local_pdf[slot] = 0.0;
  local_strategy_pdf[slot] = 0.0;
  if (restir_light_count() == 0u) return;
  uint rng = frame_rng(cell, kRestirRngLocalLights);
  float min_distance = kRestirLocalMinDistance * restir_scene_radius();
  float min_dist2 = max(min_distance * min_distance, 1e-12);
  float far_dist2 = restir_scene_radius() * restir_scene_radius();
  float g_sum = 0.0;
  float g_pick = 0.0;
  float pdf_pick = 0.0;
  uint entry_pick = 0u;
  for (uint k = 0u; k < push.local_candidates; ++k) {
    float u0 = rng_next_float(rng);
    float u1 = rng_next_float(rng);
    float u_pick = rng_next_float(rng);
    uint entry = draw_strategy_entry(u0, u1, tile_base);
    float pdf;
    vec4 p0 = strategy_entry_position(entry, pdf);
    float g = 1.0;
    if (has_point) {
      vec3 d = p0.xyz - x;
      float dist2 = floatBitsToUint(p0.w) == kLightDirectional ? far_dist2 : dot(d, d);
      // Clamped below float's overflow too: g stays positive for every light.
      g = 1.0 / min(max(dist2, min_dist2), 1e30);
    }
    g_sum += g;
    if (u_pick * g_sum < g) {
      entry_pick = entry;
      g_pick = g;
      pdf_pick = pdf;
    }
  }
  local_entry[slot] = entry_pick;
  local_pdf[slot] = g_sum > 0.0 ? pdf_pick * g_pick * float(push.local_candidates) / g_sum : 0.0;
  local_strategy_pdf[slot] = pdf_pick;
}

// A light candidate from u0 (in [0,1), after the environment's share) and u1: from the local
// light list when it is on, else one light-strategy draw. Returns the light's index and record,
// the candidate's density pdf (1 / its contribution weight, before the (1 - p_env) factor) and
// the light strategy's own density of that light (equal to pdf without the local list), and its
// light grid record where presampling has it (strategy_entry_light).
uint draw_light(float u0, float u1, uint tile_base, out GpuLight light, out float pdf,
                out float strategy_pdf, out uvec2 grid_cell) {
  if (push.local_candidates > 0u) {
    uint slot = min(uint(u0 * float(kLocalSlots)), kLocalSlots - 1u);
    pdf = local_pdf[slot];
    strategy_pdf = local_strategy_pdf[slot];
    float entry_pdf;
    return strategy_entry_light(local_entry[slot], light, entry_pdf, grid_cell);
  }
  uint index =
      strategy_entry_light(draw_strategy_entry(u0, u1, tile_base), light, pdf, grid_cell);
  strategy_pdf = pdf;
  return index;
}

// First entry of the presampled tile this workgroup draws from this frame. Runs of consecutive
// workgroups share a tile: lavapipe hands each CPU thread a contiguous range of workgroups, so
// the tile stays in that core's cache (a random tile per workgroup missed it: restir.initial
// gained 10-18% instead of 40%). The workgroup -> screen tile shuffle (push.tile_stride) spreads
// one run over the image, and the runs rotate every frame.
uint presampled_tile_base() {
  if (push.presample_tiles == 0u) return 0u;
  uint rng = frame_rng(uvec2(0u), kRestirRngPresampleTile);
  uint rotation = rng_next_uint(rng);
  // (workgroups x tiles < 2^32 up to 8K x 8K pixels with the 1024-tile maximum)
  uint run = (gl_WorkGroupID.x * push.presample_tiles) / gl_NumWorkGroups.x;
  return ((run + rotation) % push.presample_tiles) * kRestirPresampleTileSize;
}

// An environment candidate in direction l (from either strategy): its stored uv and the balance
// heuristic weight p̂ / (m_light p_light + m_bsdf p_bsdf), both densities in solid angle.
float env_candidate(ShadingPoint p, vec3 l, float p_env, float m_light, float m_bsdf,
                    out vec2 uv, out float target) {
  uv = restir_stored_uv(env_world_direction_to_uv(env_header.env, l));
  vec3 stored = env_uv_to_world_direction(env_header.env, uv);
  target = light_eval_target(restir_env_contribution(p, uv));
  if (!(target > 0.0)) return 0.0;
  float denominator = m_light * restir_env_strategy_pdf(stored, p_env);
  if (m_bsdf > 0.0) denominator += m_bsdf * bsdf_direction_pdf(p, stored);
  return safe_ratio(target, denominator);
}

// The strategies: how many candidates each draws (light, BSDF, light grid), the lights and the
// environment's share of the light strategy, and the light grid's cell of the point with the
// weights of the 27 cells around it and their sum (scene_light_grid_weights).
struct Strategies {
  uint light_count;
  float p_env;
  float m_light;
  float m_bsdf;
  float m_grid;
  uvec4 grid_cell;
  float grid_weights[kLightGridNeighbourCells];
  float grid_total;
};

Strategies restir_strategies(ShadingPoint p) {
  Strategies s;
  s.light_count = restir_light_count();
  s.p_env = restir_env_probability();
  s.m_light = float(push.light_candidates);
  s.m_bsdf = float(bsdf_candidates_at(p));
  bool grid = push.grid_candidates > 0u && s.light_count > 0u && scene_light_grid_on();
  s.m_grid = grid ? float(push.grid_candidates) : 0.0;
  s.grid_cell = grid ? scene_light_grid_cell(p.x) : uvec4(0u);
  s.grid_total = grid ? scene_light_grid_weights(s.grid_cell, p.x, p.ng, s.grid_weights) : 0.0;
  return s;
}

// The light grid strategy's density of drawing a light whose grid record is `light_cell` (its
// cell's key and its share of that cell's pick: light_cells), selection only.
float grid_selection_pdf(Strategies s, uvec2 light_cell) {
  uint k = light_grid_near_index(light_cell.x, s.grid_cell);
  if (k >= kLightGridNeighbourCells) return 0.0;
  return light_grid_pdf(s.grid_weights[k], s.grid_total, uintBitsToFloat(light_cell.y));
}

// The light grid strategy's density of a point on `light` (index `index`) whose point density
// is point_pdf (light_eval_point_pdf), area measure.
float grid_area_pdf(Strategies s, uint index, float point_pdf) {
  return grid_selection_pdf(s, light_cells.c[index]) * point_pdf;
}

// Whether there is nothing to sample (no light, no environment): no candidate is drawn.
bool strategies_empty(Strategies s) { return s.light_count == 0u && s.p_env == 0.0; }

// push.light_candidates light candidates into r.
void resample_lights(ShadingPoint p, Strategies s, uint tile_base, inout uint rng,
                     inout Reservoir r) {
  for (uint i = 0u; i < push.light_candidates; ++i) {
    float u0 = rng_next_float(rng);
    float u1 = rng_next_float(rng);
    vec2 uv = restir_stored_uv(rng_next_vec2(rng));
    float u_pick = rng_next_float(rng);
    if (restir_strategy_environment(u0, s.p_env, s.light_count)) {
      // The environment: u0 (rescaled) picks its row, the rest the column and the point.
      vec3 l, le;
      env_sample(env_header.env, vec4(u0, u1, uv), l, le);
      vec2 env_uv;
      float target;
      float weight = env_candidate(p, l, s.p_env, s.m_light, s.m_bsdf, env_uv, target);
      reservoir_update(r, light_sample_make(kEnvironmentLight, env_uv, target), weight, u_pick);
      continue;
    }
    GpuLight light;
    float pdf;
    float strategy_pdf;
    uvec2 grid_cell;
    uint index = draw_light(u0, u1, tile_base, light, pdf, strategy_pdf, grid_cell);
    float target = light_eval_target(restir_light_contribution(p, light, uv));
    float weight = safe_ratio(target, s.m_light * (1.0 - s.p_env) * pdf);
    if ((s.m_bsdf > 0.0 || s.m_grid > 0.0) && target > 0.0) {
      // Balance heuristic over the light strategy's density q (with the environment's share),
      // the BSDF's and the light grid's, times the candidate's contribution weight 1 / pdf:
      // target q / (pdf (m_light q + m_bsdf p_bsdf + m_grid p_grid)). Without the local list
      // pdf = q: the plain balance heuristic.
      float light_term = s.m_light * (1.0 - s.p_env) * strategy_pdf;
      float other_terms = 0.0;
      if (s.m_bsdf > 0.0) {
        vec3 y = light_eval_position(light, uv, p.x, restir_scene_radius());
        other_terms += s.m_bsdf * bsdf_area_pdf(p, light, y);
      }
      if (s.m_grid > 0.0) {
        if (grid_cell.x == kLightGridNoCell) grid_cell = light_cells.c[index];
        other_terms +=
            s.m_grid * grid_selection_pdf(s, grid_cell) * light_eval_point_pdf(light);
      }
      float contribution_ratio = push.local_candidates > 0u ? safe_ratio(strategy_pdf, pdf) : 1.0;
      weight = safe_ratio(target * contribution_ratio, light_term + other_terms);
    }
    reservoir_update(r, light_sample_make(index, uv, target), weight, u_pick);
  }
}

// The pixel's light grid candidates (s.m_grid, from their own random stream): a light near the
// point (scene_light_grid_draw: nothing where no cell near it has a weight, which still counts in
// M), weighed by the balance heuristic over the three strategies' densities.
void resample_grid(ShadingPoint p, Strategies s, inout uint rng, inout Reservoir r) {
  for (uint j = 0u; j < uint(s.m_grid); ++j) {
    float u_cell = rng_next_float(rng);
    float u_light = rng_next_float(rng);
    vec2 uv = restir_stored_uv(rng_next_vec2(rng));
    float u_pick = rng_next_float(rng);
    uint index = scene_light_grid_draw(s.grid_cell, s.grid_weights, s.grid_total, u_cell, u_light);
    float target = 0.0;
    float weight = 0.0;
    if (index != kInvalidLight) {
      GpuLight light = scene_light(index);
      target = light_eval_target(restir_light_contribution(p, light, uv));
      if (target > 0.0) {
        float point_pdf = light_eval_point_pdf(light);
        float denominator = s.m_light * scene_light_strategy_pdf(index, s.p_env) * point_pdf +
                            s.m_grid * grid_area_pdf(s, index, point_pdf);
        if (s.m_bsdf > 0.0) {
          vec3 y = light_eval_position(light, uv, p.x, restir_scene_radius());
          denominator += s.m_bsdf * bsdf_area_pdf(p, light, y);
        }
        weight = safe_ratio(target, denominator);
      }
    }
    reservoir_update(r, light_sample_make(index, uv, target), weight, u_pick);
  }
}

// One BSDF candidate's draws from rng: its direction l, the reservoir's u_pick, and whether it
// asks a closest-hit ray (from `origin`, where l leaves the surface's geometric side). The one
// owner of what the "closestemit" variant and restir.initial ask, in the same order.
bool bsdf_candidate_ray(ShadingPoint p, inout uint rng, out vec3 origin, out vec3 l,
                        out float u_pick) {
  float u_lobe = rng_next_float(rng);
  vec2 u_dir = rng_next_vec2(rng);
  u_pick = rng_next_float(rng);
  l = u_lobe < specular_lobe_probability(p) ? ggx_vndf_sample(p.n, p.v, p.roughness, u_dir)
                                            : cosine_sample_hemisphere(p.n, u_dir);
  origin = bvh_ray_origin(p.x, p.ng);
  return dot(l, p.ng) > 0.0;
}

// The pixel's BSDF candidates (bsdf_candidates_at) into r, from their own random stream (so the
// "closestemit" variant draws the same rays without the light candidates' draws).
void resample_bsdf(ShadingPoint p, Strategies s, inout uint rng, inout Reservoir r) {
  for (uint j = 0u; j < uint(s.m_bsdf); ++j) {
    vec3 origin;
    vec3 l;
    float u_pick;
    bool asks = bsdf_candidate_ray(p, rng, origin, l, u_pick);
    VisHit hit;
    uint index = kInvalidLight;
    vec2 uv = vec2(0.0);
    float weight = 0.0;
    float target = 0.0;
    if (asks) {
      if (vis_trace_closest(origin, l, kVisInfinity, hit)) {
        uint first = scene_instances.i[hit.instance].bvh.y;
        if (first != kInvalidLight && first + hit.primitive < s.light_count) {
          index = first + hit.primitive;
          uv = restir_stored_uv(triangle_barycentrics_to_uv(hit.u, hit.v));
        }
      } else if (s.p_env > 0.0) {
        // The ray escapes: it sees the environment in direction l.
        index = kEnvironmentLight;
        weight = env_candidate(p, l, s.p_env, s.m_light, s.m_bsdf, uv, target);
      }
    }
    if (index != kInvalidLight && index != kEnvironmentLight &&
        light_kind(scene_light(index)) == kLightTriangle) {
      target = light_eval_target(restir_contribution(p, index, uv));
      vec3 y = light_eval_position(scene_light(index), uv, p.x, restir_scene_radius());
      float denominator = s.m_light * restir_light_strategy_pdf(index, s.p_env) +
                          s.m_bsdf * bsdf_area_pdf(p, scene_light(index), y);
      if (s.m_grid > 0.0) {
        denominator +=
            s.m_grid * grid_area_pdf(s, index, light_eval_point_pdf(scene_light(index)));
      }
      weight = safe_ratio(target, denominator);
    }
    reservoir_update(r, light_sample_make(index, uv, target), weight, u_pick);
  }
}

Reservoir resample(ShadingPoint p, uvec2 cell, uint tile_base) {
  Reservoir r = reservoir_empty();
  Strategies s = restir_strategies(p);
  if (strategies_empty(s)) {
    r.M = s.m_light + s.m_bsdf + s.m_grid;
    return r;
  }
  uint rng = frame_rng(cell, kRestirRngInitial);
  resample_lights(p, s, tile_base, rng, r);
  if (s.m_grid > 0.0) {
    uint grid_rng = frame_rng(cell, kRestirRngInitialGrid);
    resample_grid(p, s, grid_rng, r);
  }
  uint bsdf_rng = frame_rng(cell, kRestirRngInitialBsdf);
  resample_bsdf(p, s, bsdf_rng, r);
  reservoir_finalize(r);
  return r;
}

// The pixel's G-buffer packed into a RestirSurface (the sky's where the G-buffer holds none).
RestirSurface gbuffer_surface(ivec2 ip, vec4 position) {
  if (gbuffer_is_sky(position.w)) return restir_surface_sky();
  vec4 normals = imageLoad(gbuffer_normal, ip);
  vec4 albedo_roughness = imageLoad(gbuffer_albedo_roughness, ip);
  float metallic = imageLoad(gbuffer_emission_metallic, ip).w;
  uint material = imageLoad(gbuffer_ids, ip).y;
  float specular = scene_materials.m[material].params.z;
  return restir_surface_pack(position, oct_decode(normals.xy), oct_decode(normals.zw),
                             albedo_roughness.rgb, albedo_roughness.a, metallic, specular,
                             material);
}

#ifdef LANTERN_VISIBILITY_HOST_CLOSEST_EMIT
// The "closestemit" variant: only the BSDF candidates' rays, as restir.initial will ask them
// (the same surface, stream and draws), into the host's closest-hit ray buffer.
void main() {
  uvec2 cell;
  if (!restir_cell(cell)) return;
  ivec2 ip = ivec2(restir_representative(cell));
  vis_host_closest_begin(restir_index(cell) * push.bsdf_candidates, push.bsdf_candidates);
  RestirSurface surface = gbuffer_surface(ip, imageLoad(gbuffer_position, ip));
  ShadingPoint p = restir_shading_point(surface, frame_constants.frame.camera_position.xyz);
  Strategies s = restir_strategies(p);
  if (p.valid && !strategies_empty(s)) {
    uint rng = frame_rng(cell, kRestirRngInitialBsdf);
    // The count resample_bsdf loops over, from the same Strategies.
    for (uint j = 0u; j < uint(s.m_bsdf); ++j) {
      vec3 origin;
      vec3 l;
      float u_pick;
      VisHit hit;
      if (bsdf_candidate_ray(p, rng, origin, l, u_pick))
        vis_trace_closest(origin, l, kVisInfinity, hit);
    }
  }
  vis_host_closest_end();
}
#else
// With push.reservoir_stride > 1, every pixel of the cell's block into pixel_surfaces
// (`surface`, the representative's, already packed).
void pack_block_surfaces(uvec2 cell, uvec2 representative, RestirSurface surface) {
  uvec2 first = cell * restir_stride();
  uvec2 last = min(first + restir_stride(), restir_size());
  for (uint y = first.y; y < last.y; ++y) {
    for (uint x = first.x; x < last.x; ++x) {
      uvec2 pixel = uvec2(x, y);
      ivec2 ip = ivec2(pixel);
      pixel_surfaces.s[restir_pixel_index(pixel)] =
          pixel == representative ? surface : gbuffer_surface(ip, imageLoad(gbuffer_position, ip));
    }
  }
}

void main() {
  uvec2 cell;
  bool inside = restir_cell(cell);
  uvec2 pixel = inside ? restir_representative(cell) : uvec2(0u);
  ivec2 ip = ivec2(pixel);
  vec4 position = inside ? imageLoad(gbuffer_position, ip) : vec4(0.0);
  uint tile_base = presampled_tile_base();
  if (push.local_candidates > 0u) {
    // Every invocation fills its slot, inside the grid or not, before any reads the list.
    fill_local_slot(cell, inside && !gbuffer_is_sky(position.w), position.xyz, tile_base);
    barrier();
  }
  if (!inside) return;
  uint index = restir_index(cell);
  RestirSurface surface = gbuffer_surface(ip, position);
  restir_surfaces.s[index] = surface;
  if (restir_stride() > 1u) pack_block_surfaces(cell, pixel, surface);

  ShadingPoint p = restir_shading_point(surface, frame_constants.frame.camera_position.xyz);
  Reservoir r = reservoir_empty();
  if (p.valid) {
    vis_host_closest_begin(index * push.bsdf_candidates, push.bsdf_candidates);
    r = resample(p, cell, tile_base);
    if ((push.flags & kRestirFlagInitialVisibility) != 0u && reservoir_has_sample(r)) {
      vec3 y = restir_light_position(p, r.selected.light_index, vec2(r.selected.u, r.selected.v));
      if (!vis_visible(p.x, y)) {
        // Keep M (the candidates were drawn) but no sample: the pick lights nothing here.
        reservoir_drop_sample(r);
      }
    }
  }
  reservoirs_out.r[index] = reservoir_pack(r);
}
#endif
