// Procedural meshes: plane, box, UV and ico spheres, binned emissive quad grids.
#include "engine/level/primitives.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/constants.hpp>
#include <map>

#include "engine/level/generators/split_mix.h"

namespace lantern {
namespace {

// Appends a quad centred at `c` spanning ±du, ±dv; its front faces along cross(du, dv).
void add_quad(Mesh& m, glm::vec3 c, glm::vec3 du, glm::vec3 dv) {
  const auto base = static_cast<std::uint32_t>(m.positions.size());
  const glm::vec3 n = glm::normalize(glm::cross(du, dv));
  const glm::vec3 corners[4] = {c - du - dv, c + du - dv, c + du + dv, c - du + dv};
  const glm::vec2 uv[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  for (int i = 0; i < 4; ++i) {
    m.positions.push_back(corners[i]);
    m.normals.push_back(n);
    m.uvs.push_back(uv[i]);
  }
  m.indices.insert(m.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
}

// Makes every triangle of a closed, origin-centred convex mesh face outwards.
void orient_outwards(Mesh& m) {
  for (std::size_t t = 0; t < m.indices.size(); t += 3) {
    const glm::vec3 a = m.positions[m.indices[t]], b = m.positions[m.indices[t + 1]],
                    c = m.positions[m.indices[t + 2]];
    if (glm::dot(glm::cross(b - a, c - a), a + b + c) < 0.0f)
      std::swap(m.indices[t + 1], m.indices[t + 2]);
  }
}

void finish_bounds(Mesh& m) {
  m.bounds = Aabb{};
  for (const glm::vec3& p : m.positions) m.bounds.grow(p);
}

}  // namespace

Mesh make_plane(glm::vec2 size) {
  Mesh m;
  m.name = "plane";
  add_quad(m, glm::vec3(0.0f), glm::vec3(0, 0, 0.5f * size.y), glm::vec3(0.5f * size.x, 0, 0));
  finish_bounds(m);
  return m;
}

Material make_lambert(float rho) {
  Material m;
  m.base_color = glm::vec4(rho, rho, rho, 1.0f);
  m.metallic = 0.0f;
  m.roughness = 1.0f;
  m.specular_factor = 0.0f;
  return m;
}

Mesh make_box(glm::vec3 size, bool inward) {
  Mesh m;
  m.name = "box";
  const glm::vec3 h = 0.5f * size;
  const glm::vec3 x(h.x, 0, 0), y(0, h.y, 0), z(0, 0, h.z);
  // (face centre offset, du, dv) with cross(du, dv) pointing out of the box.
  const glm::vec3 faces[6][3] = {{x, y, z},  {-x, z, y}, {y, z, x},
                                 {-y, x, z}, {z, x, y},  {-z, y, x}};
  for (const auto& f : faces) {
    if (inward)
      add_quad(m, f[0], f[2], f[1]);
    else
      add_quad(m, f[0], f[1], f[2]);
  }
  finish_bounds(m);
  return m;
}

Mesh make_uv_sphere(float radius, std::uint32_t segments, std::uint32_t rings) {
  segments = std::max(segments, 3u);
  rings = std::max(rings, 2u);
  Mesh m;
  m.name = "uv_sphere";
  const float pi = glm::pi<float>();
  for (std::uint32_t r = 0; r <= rings; ++r) {
    const float theta = pi * static_cast<float>(r) / static_cast<float>(rings);
    for (std::uint32_t s = 0; s <= segments; ++s) {
      const float phi = 2.0f * pi * static_cast<float>(s) / static_cast<float>(segments);
      const glm::vec3 n(std::sin(theta) * std::cos(phi), std::cos(theta),
                        std::sin(theta) * std::sin(phi));
      m.positions.push_back(radius * n);
      m.normals.push_back(n);
      m.uvs.emplace_back(static_cast<float>(s) / static_cast<float>(segments),
                         static_cast<float>(r) / static_cast<float>(rings));
    }
  }
  const std::uint32_t row = segments + 1;
  for (std::uint32_t r = 0; r < rings; ++r) {
    for (std::uint32_t s = 0; s < segments; ++s) {
      const std::uint32_t a = r * row + s, b = (r + 1) * row + s, c = b + 1, d = a + 1;
      if (r != 0) m.indices.insert(m.indices.end(), {a, b, d});  // skip the pole sliver
      if (r != rings - 1) m.indices.insert(m.indices.end(), {d, b, c});
    }
  }
  orient_outwards(m);
  finish_bounds(m);
  return m;
}

Mesh make_ico_sphere(float radius, std::uint32_t subdivisions) {
  const float t = (1.0f + std::sqrt(5.0f)) * 0.5f;
  std::vector<glm::vec3> p = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0},
                              {0, -1, t}, {0, 1, t}, {0, -1, -t}, {0, 1, -t},
                              {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  for (glm::vec3& v : p) v = glm::normalize(v);
  std::vector<std::uint32_t> idx = {0, 11, 5, 0, 5,  1,  0,  1,  7,  0,  7, 10, 0, 10, 11,
                                    1, 5,  9, 5, 11, 4,  11, 10, 2,  10, 7, 6,  7, 1,  8,
                                    3, 9,  4, 3, 4,  2,  3,  2,  6,  3,  6, 8,  3, 8,  9,
                                    4, 9,  5, 2, 4,  11, 6,  2,  10, 8,  6, 7,  9, 8,  1};
  for (std::uint32_t level = 0; level < subdivisions; ++level) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> midpoints;
    auto mid = [&](std::uint32_t a, std::uint32_t b) {
      auto key = std::minmax(a, b);
      auto [it, inserted] = midpoints.try_emplace({key.first, key.second}, 0u);
      if (inserted) {
        it->second = static_cast<std::uint32_t>(p.size());
        p.push_back(glm::normalize(p[a] + p[b]));
      }
      return it->second;
    };
    std::vector<std::uint32_t> next;
    next.reserve(idx.size() * 4);
    for (std::size_t i = 0; i < idx.size(); i += 3) {
      const std::uint32_t a = idx[i], b = idx[i + 1], c = idx[i + 2];
      const std::uint32_t ab = mid(a, b), bc = mid(b, c), ca = mid(c, a);
      next.insert(next.end(), {a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca});
    }
    idx = std::move(next);
  }
  Mesh m;
  m.name = "ico_sphere";
  for (const glm::vec3& n : p) {
    m.positions.push_back(radius * n);
    m.normals.push_back(n);
    m.uvs.emplace_back(0.5f + std::atan2(n.z, n.x) / (2.0f * glm::pi<float>()),
                       std::acos(std::clamp(n.y, -1.0f, 1.0f)) / glm::pi<float>());
  }
  m.indices = std::move(idx);
  orient_outwards(m);
  finish_bounds(m);
  return m;
}

void append_transformed(Mesh& dst, const Mesh& src, const glm::mat4& m) {
  const auto base = static_cast<std::uint32_t>(dst.positions.size());
  const glm::mat3 normal_matrix = glm::transpose(glm::inverse(glm::mat3(m)));
  for (std::size_t i = 0; i < src.positions.size(); ++i) {
    dst.positions.push_back(glm::vec3(m * glm::vec4(src.positions[i], 1.0f)));
    dst.normals.push_back(glm::normalize(normal_matrix * src.normals[i]));
    dst.uvs.push_back(src.uvs.empty() ? glm::vec2(0.0f) : src.uvs[i]);
  }
  for (std::uint32_t idx : src.indices) dst.indices.push_back(base + idx);
  // A mirroring transform turns triangles inside out: restore counter-clockwise fronts.
  if (glm::determinant(glm::mat3(m)) < 0.0f)
    for (std::size_t t = dst.indices.size() - src.indices.size(); t < dst.indices.size(); t += 3)
      std::swap(dst.indices[t + 1], dst.indices[t + 2]);
  finish_bounds(dst);
}

float quad_grid_radiance(const EmissiveQuadGrid& g, std::uint64_t index) {
  const std::uint64_t count = std::uint64_t{g.nx} * g.ny;
  const float t = count > 1 ? static_cast<float>(index) / static_cast<float>(count - 1) : 0.0f;
  const bool log_ok = g.radiance_min > 0.0f;
  auto ramp = [&](float x) {
    return log_ok && g.pattern != "linear"
               ? g.radiance_min * std::pow(g.radiance_max / g.radiance_min, x)
               : g.radiance_min + x * (g.radiance_max - g.radiance_min);
  };
  if (g.pattern == "uniform") return g.radiance_min;
  if (g.pattern == "linear" || g.pattern == "log") return ramp(t);
  if (g.pattern == "checker") {
    const std::uint64_t i = index % g.nx, j = index / g.nx;
    return (i + j) % 2 ? g.radiance_max : g.radiance_min;
  }
  SplitMix rng(g.seed * 0x100000001B3ull + index);  // "random"
  return ramp(rng.uniform());
}

std::vector<EmissiveQuadBin> make_emissive_quad_grid(const EmissiveQuadGrid& g) {
  const bool log_bins = g.radiance_min > 0.0f && g.pattern != "linear";
  const std::uint32_t levels = std::max(g.levels, 1u);
  auto to_unit = [&](float r) {
    if (g.radiance_max <= g.radiance_min) return 0.0f;
    return log_bins ? std::log(r / g.radiance_min) / std::log(g.radiance_max / g.radiance_min)
                    : (r - g.radiance_min) / (g.radiance_max - g.radiance_min);
  };
  auto from_unit = [&](float x) {
    return log_bins ? g.radiance_min * std::pow(g.radiance_max / g.radiance_min, x)
                    : g.radiance_min + x * (g.radiance_max - g.radiance_min);
  };
  std::map<std::uint32_t, EmissiveQuadBin> bins;
  const glm::vec3 du = 0.5f * g.size.x * glm::normalize(g.u);
  const glm::vec3 dv = 0.5f * g.size.y * glm::normalize(g.v);
  for (std::uint32_t j = 0; j < g.ny; ++j) {
    for (std::uint32_t i = 0; i < g.nx; ++i) {
      const float r = quad_grid_radiance(g, std::uint64_t{j} * g.nx + i);
      const auto bin =
          levels == 1 ? 0u
                      : static_cast<std::uint32_t>(std::lround(std::clamp(to_unit(r), 0.0f, 1.0f) *
                                                               static_cast<float>(levels - 1)));
      EmissiveQuadBin& b = bins[bin];
      b.radiance = levels == 1
                       ? g.radiance_max
                       : from_unit(static_cast<float>(bin) / static_cast<float>(levels - 1));
      const glm::vec3 c =
          g.origin + (static_cast<float>(i) + 0.5f) * g.u + (static_cast<float>(j) + 0.5f) * g.v;
      add_quad(b.mesh, c, du, dv);
    }
  }
  std::vector<EmissiveQuadBin> out;
  for (auto& [bin, b] : bins) {
    b.mesh.name = "emissive_quad_grid";
    finish_bounds(b.mesh);
    out.push_back(std::move(b));
  }
  return out;
}

}  // namespace lantern
