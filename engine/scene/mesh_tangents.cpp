// Angle-weighted per-vertex tangent frames (mesh_tangents.h).
#include "engine/scene/mesh_tangents.h"

#include <algorithm>
#include <cmath>

namespace lantern {
namespace {

// v projected into the plane of unit n, normalised; zero when v is (nearly) along n or not finite.
glm::vec3 in_plane(const glm::vec3& v, const glm::vec3& n) {
  const glm::vec3 p = v - n * glm::dot(n, v);
  const float len2 = glm::dot(p, p);
  return len2 > 1e-30f && std::isfinite(len2) ? p / std::sqrt(len2) : glm::vec3(0.0f);
}

// The angle at corner a of triangle (a, b, c).
float corner_angle(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
  const glm::vec3 u = b - a, v = c - a;
  const float denom = std::sqrt(glm::dot(u, u) * glm::dot(v, v));
  if (!(denom > 0.0f)) return 0.0f;
  return std::acos(std::clamp(glm::dot(u, v) / denom, -1.0f, 1.0f));
}

}  // namespace

std::vector<glm::vec4> generate_tangents(const Mesh& mesh, std::uint32_t texcoord_set) {
  const std::size_t n = mesh.positions.size();
  std::vector<glm::vec4> out(n, glm::vec4(0.0f));
  const std::vector<glm::vec2>& uvs = mesh.texcoords(texcoord_set);
  if (uvs.size() != n || mesh.normals.size() != n) return out;
  std::vector<glm::vec3> tangent_sum(n, glm::vec3(0.0f));
  std::vector<glm::vec3> bitangent_sum(n, glm::vec3(0.0f));
  for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    const std::uint32_t corner[3] = {mesh.indices[t], mesh.indices[t + 1], mesh.indices[t + 2]};
    const glm::vec3& p0 = mesh.positions[corner[0]];
    const glm::vec3 e1 = mesh.positions[corner[1]] - p0;
    const glm::vec3 e2 = mesh.positions[corner[2]] - p0;
    const glm::vec2 d1 = uvs[corner[1]] - uvs[corner[0]];
    const glm::vec2 d2 = uvs[corner[2]] - uvs[corner[0]];
    const float det = d1.x * d2.y - d1.y * d2.x;
    if (!(std::abs(det) > 0.0f) || !std::isfinite(det)) continue;  // no uv mapping here
    // dp/du and dp/dv of the triangle (the sign of det carries its uv orientation).
    const glm::vec3 dp_du = (e1 * d2.y - e2 * d1.y) / det;
    const glm::vec3 dp_dv = (e2 * d1.x - e1 * d2.x) / det;
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t v = corner[k];
      const float angle = corner_angle(mesh.positions[v], mesh.positions[corner[(k + 1) % 3]],
                                       mesh.positions[corner[(k + 2) % 3]]);
      tangent_sum[v] += angle * in_plane(dp_du, mesh.normals[v]);
      bitangent_sum[v] += angle * in_plane(dp_dv, mesh.normals[v]);
    }
  }
  for (std::size_t v = 0; v < n; ++v) {
    const glm::vec3 t = in_plane(tangent_sum[v], mesh.normals[v]);
    if (glm::dot(t, t) == 0.0f) continue;
    // up = -dp/dv (glTF's v runs down the image): w = +1 when cross(n, t) points that way.
    const float w = glm::dot(glm::cross(mesh.normals[v], t), bitangent_sum[v]) > 0.0f ? -1.0f : 1.0f;
    out[v] = glm::vec4(t, w);
  }
  return out;
}

}  // namespace lantern
