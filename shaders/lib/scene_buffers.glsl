// The scene as every pass reads it: declares each scene buffer once, at the binding its slot
// names (shared/scene_bindings.h), under the name SceneHandles::bind binds it by
// (lighting/scene/scene_buffers.h):
//   frame_constants.frame (FrameConstants), scene_vertices.v[], scene_indices.i[],
//   scene_materials.m[], scene_instances.i[], scene_light(i) and scene_light_alias(i) (the
//   lights and their alias tables through rgba32ui texel views; scene_light_sample and
//   scene_light_selection_pdf draw and weigh a light by power),
//   light_previous_to_current.index[] (uint per last frame's light: its current index or
//   kInvalidLight), the BVH (lib/bvh_traverse.glsl: bvh_header, bvh_*_texels; in the rayquery
//   variant instead the TLAS scene_tlas at kSceneTlas) and the
//   environment (lib/environment.glsl: env_header, env_texels, env_marginal, env_conditional),
//   the material textures scene_textures.t[], scene_texels.w[], scene_textured_emitters.e[]
//   (lib/textures.glsl's texture_sample), scene_vertex_tangents.t[] and
//   scene_vertex_texcoords1.uv[] (scene_vertex_texcoord picks a vertex's set), and the media
//   (lib/volumes.glsl: scene_volumes, scene_volume_cells, scene_volume_values;
//   scene_transmittance), and the light grid (shared/light_grid.h: light_grid.g and .words[],
//   light_cells.c[]; scene_light_grid_weights and scene_light_grid_draw weigh the cells near a
//   point and draw a light from them).
// Then lib/visibility.glsl's vis_trace_closest / vis_visible and frame_rng are available. A pass
// declares its own resources from kPassBindingBase on: layout(binding = PASS_BINDING(0)).
#ifndef LANTERN_LIB_SCENE_BUFFERS_GLSL
#define LANTERN_LIB_SCENE_BUFFERS_GLSL

#extension GL_GOOGLE_include_directive : require

#include "shared/alias_table.h"
#include "shared/light_grid.h"
#include "shared/lights.h"
#include "shared/rng.h"
#include "shared/scene.h"
#include "shared/scene_bindings.h"
#include "shared/textures.h"

#include "lib/texel_records.glsl"

#define PASS_BINDING(i) (kPassBindingBase + (i))

layout(std430, binding = kSceneFrameConstants) restrict readonly buffer FrameBuffer {
  FrameConstants frame;
} frame_constants;
layout(std430, binding = kSceneVertices) restrict readonly buffer VertexBuffer {
  GpuVertex v[];
} scene_vertices;
layout(std430, binding = kSceneIndices) restrict readonly buffer IndexBuffer {
  uint i[];
} scene_indices;
layout(std430, binding = kSceneMaterials) restrict readonly buffer MaterialBuffer {
  GpuMaterial m[];
} scene_materials;
layout(std430, binding = kSceneInstances) restrict readonly buffer InstanceBuffer {
  GpuInstance i[];
} scene_instances;
// The lights through an rgba32ui texel view (kGpuLightTexels texels each): lavapipe fetches
// texels faster than it loads storage buffers, and p̂ reads a light record at every evaluation
// (restir.temporal 0.86x, restir.spatial 0.83x the time with storage-buffer reads, night_market).
layout(binding = kSceneLights) uniform utextureBuffer scene_light_texels;
GpuLight scene_light(uint index) {
  return gpu_light_fetch(scene_light_texels, kGpuLightTexels * index);
}
// The alias table through an rgba32ui texel view (one texel per AliasEntry), as the lights.
layout(binding = kSceneLightAlias) uniform utextureBuffer light_alias_texels;
AliasEntry scene_light_alias(uint slot) {
  uvec4 t = texelFetch(light_alias_texels, int(slot));
  return AliasEntry(uintBitsToFloat(t.x), t.y, uintBitsToFloat(t.z), t.w);
}
// A light drawn in proportion to its power from u0, u1 in [0,1), through the two groups'
// tables (shared/alias_table.h: the emissive triangles, counts.z of them, then the analytic
// lights; scene.y the triangles' share), and the probability of drawing light `index` so. Only
// while frame.counts.x > 0 (some light has power).
uint scene_light_sample(float u0, float u1) {
  uint slot = alias_group_slot(frame_constants.frame.counts.x, frame_constants.frame.counts.z,
                               frame_constants.frame.scene.y, u0);
  return alias_select(u1, scene_light_alias(slot), slot);
}
float scene_light_selection_pdf(uint index) {
  return alias_group_pdf(scene_light_alias(index).pdf, index, frame_constants.frame.counts.z,
                         frame_constants.frame.scene.y);
}
// A light-strategy draw u_select in [0,1) goes to the environment below p_env (its share,
// env_header.env.params.x: 0 without a map, 1 when no emitter has power) and to the lights above
// it. For the lights it is rescaled to [0,1), scene_light_sample's u0, and light `index` is then
// drawn with probability scene_light_strategy_pdf. One form for every integrator, so their
// selections agree to the bit.
float scene_light_draw_u0(float u_select, float p_env) {
  return clamp((u_select - p_env) / max(1.0 - p_env, 1e-30), 0.0, 0.99999994);
}
float scene_light_strategy_pdf(uint index, float p_env) {
  return (1.0 - p_env) * scene_light_selection_pdf(index);
}
layout(std430, binding = kSceneLightPreviousToCurrent) restrict readonly buffer RemapBuffer {
  uint index[];
} light_previous_to_current;
// Last frame's light index `previous` as this frame's (kInvalidLight for a light that is gone).
// While every light keeps its index (frame.history.y) the map is the identity and is not read:
// one read in no order per history sample, 4 MB of map at 10^6 lights.
uint scene_light_from_previous(uint previous) {
  if (previous >= frame_constants.frame.history.x) return kInvalidLight;
  return frame_constants.frame.history.y != 0u ? previous
                                               : light_previous_to_current.index[previous];
}

// Material textures (shared/textures.h; one zeroed stand-in element each when the level has
// none, and then no material or light names a record).
layout(std430, binding = kSceneTextures) restrict readonly buffer TextureBuffer {
  GpuTexture t[];
} scene_textures;
layout(std430, binding = kSceneTexels) restrict readonly buffer TexelBuffer {
  uint w[];
} scene_texels;
layout(std430, binding = kSceneTexturedEmitters) restrict readonly buffer TexturedEmitterBuffer {
  GpuTexturedEmitter e[];
} scene_textured_emitters;
// Vertex tangents parallel to scene_vertices (Mesh::tangents: xyz object-space +u direction, w
// the handedness, 0 = none): filled only when a material has a normal texture, else one zeroed
// stand-in element (and no material samples a normal texture).
layout(std430, binding = kSceneVertexTangents) restrict readonly buffer VertexTangentBuffer {
  vec4 t[];
} scene_vertex_tangents;
// TEXCOORD_1 parallel to scene_vertices (zero for meshes without one): filled only when a
// texture samples set 1, else one zeroed stand-in element.
layout(std430, binding = kSceneVertexTexcoords1) restrict readonly buffer VertexTexcoord1Buffer {
  vec2 uv[];
} scene_vertex_texcoords1;
#include "lib/textures.glsl"

// Whether the level has TEXCOORD_1 at all: a real array holds at least one mesh (>= 3 vertices,
// 24 bytes), the stand-in of a level without it is GpuScene's 16-byte minimum (2 entries).
bool scene_has_texcoords1() { return scene_vertex_texcoords1.uv.length() > 2; }

// Texcoord set `set` (0 or 1) of scene vertex `vertex`: GpuVertex's TEXCOORD_0, or TEXCOORD_1.
vec2 scene_vertex_texcoord(uint vertex, uint set) {
  if (set == 0u)
    return vec2(scene_vertices.v[vertex].position_u.w, scene_vertices.v[vertex].normal_v.w);
  return vertex < uint(scene_vertex_texcoords1.uv.length()) ? scene_vertex_texcoords1.uv[vertex]
                                                             : vec2(0.0);
}
// The texcoord set texture record `texture` samples (GpuTexture.transform_u.w).
uint scene_texture_set(uint texture) {
  return texture_texcoord_set(scene_textures.t[texture]);
}

// Radiance factor of a textured triangle light (GpuLight.radiance.w names its record) at
// barycentrics (b1, b2): the emissive texture at the interpolated uv, at the record's level of
// detail. shared/light_eval.h's light_eval_radiance calls it.
vec3 scene_textured_emitter_radiance(uint record, float b1, float b2) {
  GpuTexturedEmitter e = scene_textured_emitters.e[record];
  vec2 uv = (1.0 - b1 - b2) * e.uv01.xy + b1 * e.uv01.zw + b2 * e.uv2_tex.xy;
  return texture_sample(floatBitsToUint(e.uv2_tex.z), uv, e.uv2_tex.w).rgb;
}

// Whether a ray's hit on triangle `primitive` of `instance` at barycentrics (u, v) counts: false
// where the instance's alpha-tested material cuts the surface out (base colour alpha x texture
// alpha below the cutoff; texture level 0). The BVH asks only for instances flagged
// kBvhInstanceAlphaTested (shared/bvh.h), so opaque geometry pays nothing.
bool scene_alpha_accept(uint instance, uint primitive, float u, float v) {
  uvec4 geometry = scene_instances.i[instance].geometry;
  GpuMaterial m = scene_materials.m[geometry.x];
  float cutoff = m.params.w;
  if (!(cutoff > 0.0)) return true;
  float alpha = m.base_color.a;
  if (m.textures.x != kNoTexture) {
    uint base = geometry.y + 3u * primitive;
    GpuTexture t = scene_textures.t[m.textures.x];  // loaded once: its set, then its texels
    uint set = texture_texcoord_set(t);
    vec2 uv = (1.0 - u - v) * scene_vertex_texcoord(geometry.w + scene_indices.i[base], set) +
              u * scene_vertex_texcoord(geometry.w + scene_indices.i[base + 1u], set) +
              v * scene_vertex_texcoord(geometry.w + scene_indices.i[base + 2u], set);
    alpha *= texture_sample_record(t, uv, 0.0).a;
  }
  return alpha >= cutoff;
}
#define LANTERN_SCENE_ALPHA_TEST

// The light grid (shared/light_grid.h): the header, then its cells and cell-ordered lights.
layout(std430, binding = kSceneLightGrid) restrict readonly buffer LightGridBuffer {
  GpuLightGrid g;
  uint words[];
} light_grid;
layout(std430, binding = kSceneLightCells) restrict readonly buffer LightCellBuffer {
  uvec2 c[];
} light_cells;

bool scene_light_grid_on() { return light_grid.g.origin_cell.w > 0.0; }
uvec4 scene_light_grid_cell(vec3 x) { return light_grid_cell(light_grid.g, x); }

// The weights of the 27 cells around a point x (geometric normal n) in `cell`
// (scene_light_grid_cell): shared/light_grid.h's light_grid_weight of each, 0 for an empty cell
// or one outside the grid. Returns their sum.
float scene_light_grid_weights(uvec4 cell, vec3 x, vec3 n,
                               out float weights[kLightGridNeighbourCells]) {
  float total = 0.0;
  for (uint k = 0u; k < kLightGridNeighbourCells; ++k) {
    weights[k] = 0.0;
    uvec4 neighbour;
    if (!light_grid_neighbour(light_grid.g, cell, k, neighbour)) continue;
    // An empty cell's power is 0.
    uint w = kLightGridCellWords * light_grid_index(light_grid.g, neighbour);
    float power = uintBitsToFloat(light_grid.words[w + 2u]);
    weights[k] = light_grid_weight(light_grid.g, neighbour, power, x, n);
    total += weights[k];
  }
  return total;
}

// A light drawn near a point in `cell` from u_cell, u_light in [0,1): one of the 27 cells in
// proportion to `weights` (scene_light_grid_weights, summing to `total`), then one of its lights
// by the cell's alias table; kInvalidLight when every weight is 0. Light l comes with probability
// light_grid_pdf of its cell's weight (light_grid_near_index), `total` and its light_cells share.
uint scene_light_grid_draw(uvec4 cell, float weights[kLightGridNeighbourCells], float total,
                           float u_cell, float u_light) {
  if (!(total > 0.0)) return kInvalidLight;
  // The first cell whose running sum passes u_cell x total; rounding past the last sum takes the
  // last cell with a weight.
  float target = u_cell * total;
  float sum = 0.0;
  uint k = kLightGridNeighbourCells;
  for (uint j = 0u; j < kLightGridNeighbourCells; ++j) {
    if (!(weights[j] > 0.0)) continue;
    k = j;
    sum += weights[j];
    if (target < sum) break;
  }
  uvec4 neighbour;
  light_grid_neighbour(light_grid.g, cell, k, neighbour);
  uint w = kLightGridCellWords * light_grid_index(light_grid.g, neighbour);
  float slot_u;
  uint slot = light_grid_slot(light_grid.words[w + 1u], u_light, slot_u);
  uint e = light_grid_cell_words(light_grid.g) + kLightGridEntryWords * (light_grid.words[w] + slot);
  GpuLightGridEntry entry = GpuLightGridEntry(
      light_grid.words[e], uintBitsToFloat(light_grid.words[e + 1u]), light_grid.words[e + 2u]);
  return light_grid_pick(entry, slot_u);
}

#define VIS_BINDING_BASE kSceneBvhHeader
#define VIS_TLAS_BINDING kSceneTlas
#include "lib/visibility.glsl"
#define ENV_BINDING_BASE kSceneEnvHeader
#include "lib/environment.glsl"
#include "lib/volumes.glsl"

// The random stream of `pixel` in pass `pass` this frame (the frame's index and seed are the
// frame constants').
uint frame_rng(uvec2 pixel, uint pass) {
  return rng_init(pixel, frame_constants.frame.frame.z, frame_constants.frame.frame.w, pass);
}

#endif
