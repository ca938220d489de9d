#version 460
// Build-time check that the shared volume math (shared/volume.h, shared/volume_grid.h) compiles
// as GLSL when called: glslang drops uncalled functions, so each one is called once here, with
// the grid fetches and the tracking callback defined the way a volume pass defines them.
#extension GL_GOOGLE_include_directive : require

#include "shared/volume.h"

layout(local_size_x = 64) in;

layout(std430, binding = 0) readonly buffer Volumes { GpuVolume volumes[]; };
layout(std430, binding = 1) readonly buffer Cells { GpuVolumeCell volume_cells[]; };
layout(std430, binding = 2) readonly buffer Values { float volume_values[]; };
layout(std430, binding = 3) buffer Out { vec4 results[]; };

GpuVolumeCell volume_fetch_cell(uint i) { return volume_cells[i]; }
float volume_fetch_value(uint i) { return volume_values[i]; }

#include "shared/volume_grid.h"

vec3 medium_extinction(uint medium, vec3 p) {
  GpuVolume v = volumes[medium];
  return volume_extinction(v, volume_density_index(v, p));
}

void main() {
  uint index = gl_GlobalInvocationID.x;
  uint rng = rng_init(uvec2(index, 0u), 1u, 2u, 3u);
  GpuVolume v = volumes[0];
  vec3 o = vec3(v.world_to_index * vec4(0.0f, 1.0f, 0.0f, 1.0f));
  vec3 d = vec3(v.world_to_index * vec4(0.0f, 0.0f, -1.0f, 0.0f));
  float majorant = volume_majorant_index(v, o);
  vec3 t_ratio = ratio_tracking(0u, o, d, 0.0f, 4.0f, majorant, 0.1f, rng);
  GpuVolumeCell cell = volume_fetch_cell(volume_cell_index(v, volume_cell_of(v, o)));
  vec3 control = volume_extinction(v, cell.min_density);
  float residual = (cell.max_density - cell.min_density) * v.absorption.w;
  vec3 t_residual = residual_ratio_tracking(0u, o, d, 0.0f, 4.0f, control, residual, 0.0f, rng);
  vec3 w = hg_sample(normalize(d), v.scattering.w, rng_next_vec2(rng));
  float pdf_eq;
  float t_eq = equiangular_sample(o, d, vec3(1.0f), 0.0f, 4.0f, rng_next_float(rng), pdf_eq);
  float t_exp = exponential_sample_truncated(majorant, 4.0f, rng_next_float(rng));
  vec3 t_grid = volume_transmittance_ratio(0u, v, o, d, 0.0f, 4.0f, 0.1f, rng) +
                volume_transmittance_residual(0u, v, o, d, 0.0f, 4.0f, 0.1f, rng);
  results[index] = vec4(t_ratio + t_residual + w + t_grid, hg_pdf(normalize(d), w, 0.5f) + pdf_eq +
                        equiangular_pdf(o, d, vec3(1.0f), 0.0f, 4.0f, t_eq) +
                        exponential_pdf_truncated(majorant, 4.0f, t_exp) +
                        exponential_pdf(majorant, exponential_sample(majorant, 0.5f)) +
                        exponential_survival(majorant, 1.0f));
}
