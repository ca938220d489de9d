// Procedural meshes for levels: plane, box, spheres and grids of emissive quads (and a plain
// Lambertian material). All are centred
// on the origin (the grid is placed by its own origin/axes) with outward normals and CCW fronts.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "engine/scene/material.h"
#include "engine/scene/mesh.h"

namespace lantern {

// A plane in XZ facing +Y, `size` = (x extent, z extent).
Mesh make_plane(glm::vec2 size);
// An axis-aligned box with `size` = full extents; `inward` flips faces (a room seen from inside).
Mesh make_box(glm::vec3 size, bool inward = false);
// A UV sphere with `segments` around and `rings` from pole to pole.
Mesh make_uv_sphere(float radius, std::uint32_t segments, std::uint32_t rings);
// An icosphere: `subdivisions` 0 = icosahedron (20 triangles), each level x4.
Mesh make_ico_sphere(float radius, std::uint32_t subdivisions);

// A grey Lambertian material of albedo `rho` (no metal, no specular layer, roughness 1): the
// surface closed-form lighting tests shade.
Material make_lambert(float rho);

// Appends `src` transformed by `m` to `dst` (normals by the inverse transpose): generators merge
// many small static pieces into one mesh per material.
void append_transformed(Mesh& dst, const Mesh& src, const glm::mat4& m);

// A grid of nx x ny emissive quads: cell (i, j) is centred at origin + (i + 0.5) u + (j + 0.5) v
// and spans size.x along u-hat and size.y along v-hat; it faces along normalize(cross(u, v)).
// Radiances are quantised into `levels` bins (one mesh + material each) so huge grids stay cheap.
struct EmissiveQuadGrid {
  glm::vec3 origin{0.0f};
  glm::vec3 u{1.0f, 0.0f, 0.0f};  // cell pitch along the first axis
  glm::vec3 v{0.0f, 0.0f, 1.0f};  // cell pitch along the second axis
  std::uint32_t nx = 1, ny = 1;
  glm::vec2 size{0.5f};       // quad size in metres
  glm::vec3 color{1.0f};      // emitted radiance colour (multiplies the scalar radiance)
  float radiance_min = 1.0f;  // W/(sr·m²)
  float radiance_max = 1.0f;
  // "uniform" (min), "linear" / "log" ramps over the cells in order, "checker" (min/max),
  // "random" (log-uniform from `seed`).
  std::string pattern = "log";
  std::uint32_t seed = 1;
  std::uint32_t levels = 16;
};

struct EmissiveQuadBin {
  float radiance = 0.0f;  // scalar radiance of every quad in the bin
  Mesh mesh;
};

// The scalar radiance of cell `index` (row-major, 0 .. nx*ny-1) before binning.
float quad_grid_radiance(const EmissiveQuadGrid& grid, std::uint64_t index);
std::vector<EmissiveQuadBin> make_emissive_quad_grid(const EmissiveQuadGrid& grid);

}  // namespace lantern
