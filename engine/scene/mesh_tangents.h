// Per-vertex tangent frames for normal mapping, generated the way MikkTSpace (the glTF default
// when an asset has no TANGENT) builds them on meshes whose vertices are not shared across a uv
// mirror seam: each triangle's uv tangent and bitangent, projected into the vertex normal's plane
// and normalised, summed at each corner weighted by the corner's angle; the tangent is the sum
// orthonormalised against the vertex normal, and w is the handedness of the summed bitangent
// (glTF: up = w * cross(normal, tangent), up pointing towards decreasing v). Where MikkTSpace
// would split a vertex (triangles of opposite handedness, or tangents that cancel) this keeps
// one frame per vertex: the majority's handedness.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

#include "engine/scene/mesh.h"

namespace lantern {

// One tangent per vertex of `mesh` (same count as positions), for the uv mapping of texcoord
// set `texcoord_set` (the normal texture's). Needs normals and those uvs; a vertex
// that no triangle with a usable uv mapping touches (or whose tangents cancel) gets w = 0:
// "no vertex frame", and the shader falls back to its triangle's frame there.
std::vector<glm::vec4> generate_tangents(const Mesh& mesh, std::uint32_t texcoord_set = 0);

}  // namespace lantern
