// Mesh checks and repair: finite data, index range, degenerate triangles, normals, bounds.
#include "engine/level/mesh_validation.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "engine/core/error.h"
#include "engine/scene/finite.h"

namespace lantern {
namespace {

template <class V>
void require_finite(const std::vector<V>& values, const std::string& where, const char* attribute) {
  for (std::size_t i = 0; i < values.size(); ++i)
    if (!all_finite(values[i]))
      throw InputError(
          fmt::format("{}: {} of vertex {} is not finite (NaN or Inf)", where, attribute, i));
}

}  // namespace

void finalize_mesh(Mesh& mesh, const std::string& where, LoadDiagnostics& diagnostics) {
  const std::size_t n = mesh.positions.size();
  if (!mesh.normals.empty() && mesh.normals.size() != n)
    throw InputError(fmt::format("{}: {} normals for {} positions", where, mesh.normals.size(), n));
  if (!mesh.uvs.empty() && mesh.uvs.size() != n)
    throw InputError(fmt::format("{}: {} uvs for {} positions", where, mesh.uvs.size(), n));
  if (!mesh.uvs1.empty() && mesh.uvs1.size() != n)
    throw InputError(
        fmt::format("{}: {} TEXCOORD_1 uvs for {} positions", where, mesh.uvs1.size(), n));
  if (!mesh.tangents.empty() && mesh.tangents.size() != n)
    throw InputError(
        fmt::format("{}: {} tangents for {} positions", where, mesh.tangents.size(), n));
  if (mesh.indices.size() % 3 != 0)
    throw InputError(fmt::format("{}: {} indices is not a whole number of triangles", where,
                                 mesh.indices.size()));
  require_finite(mesh.positions, where, "position");
  require_finite(mesh.normals, where, "normal");
  require_finite(mesh.uvs, where, "uv");
  require_finite(mesh.uvs1, where, "TEXCOORD_1 uv");
  require_finite(mesh.tangents, where, "tangent");
  // Tangents: unit xyz and w = +-1 (glTF); a zero tangent is "no vertex frame" (w = 0), which
  // the shader answers with its triangle's frame.
  for (glm::vec4& t : mesh.tangents) {
    const float len = glm::length(glm::vec3(t));
    t = len > 0.0f ? glm::vec4(glm::vec3(t) / len, t.w < 0.0f ? -1.0f : 1.0f) : glm::vec4(0.0f);
  }

  // Drop zero-area triangles (in place), counting them.
  std::size_t kept = 0;
  for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
    const std::uint32_t a = mesh.indices[t], b = mesh.indices[t + 1], c = mesh.indices[t + 2];
    if (a >= n || b >= n || c >= n)
      throw InputError(fmt::format("{}: triangle {} uses vertex {} but the mesh has {} vertices",
                                   where, t / 3, std::max({a, b, c}), n));
    const glm::vec3 e1 = mesh.positions[b] - mesh.positions[a];
    const glm::vec3 e2 = mesh.positions[c] - mesh.positions[a];
    const float area2 = glm::length(glm::cross(e1, e2));
    const float scale = std::max(glm::dot(e1, e1), glm::dot(e2, e2));
    if (!(area2 > 1e-7f * scale) || scale == 0.0f) {
      ++diagnostics.degenerate_triangles;
      continue;
    }
    mesh.indices[kept++] = a;
    mesh.indices[kept++] = b;
    mesh.indices[kept++] = c;
  }
  mesh.indices.resize(kept);

  // Normals: area-weighted vertex normals when missing; face normal where a given one is zero.
  const bool computed = mesh.normals.empty();
  if (computed) mesh.normals.assign(n, glm::vec3(0.0f));
  std::vector<glm::vec3> face_fallback;
  for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
    const std::uint32_t i0 = mesh.indices[t], i1 = mesh.indices[t + 1], i2 = mesh.indices[t + 2];
    const glm::vec3 fn = glm::cross(mesh.positions[i1] - mesh.positions[i0],
                                    mesh.positions[i2] - mesh.positions[i0]);
    for (std::uint32_t i : {i0, i1, i2}) {
      if (computed)
        mesh.normals[i] += fn;
      else if (glm::dot(mesh.normals[i], mesh.normals[i]) < 1e-20f)
        mesh.normals[i] = fn;
    }
  }
  for (glm::vec3& nrm : mesh.normals) {
    const float len = glm::length(nrm);
    nrm = len > 0.0f ? nrm / len : glm::vec3(0.0f, 1.0f, 0.0f);
  }

  mesh.bounds = Aabb{};
  for (const glm::vec3& p : mesh.positions) mesh.bounds.grow(p);
}

}  // namespace lantern
