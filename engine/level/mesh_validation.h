// Final checks on a mesh built by a loader: finite vertex data, indices in range, degenerate
// (zero-area) triangles dropped and counted, missing normals computed, given tangents normalised
// (w to +-1), bounds filled.
#pragma once

#include <cstdint>
#include <string>

#include "engine/scene/mesh.h"

namespace lantern {

// Accumulates what the loading of one level skipped; the loader warns once at the end.
struct LoadDiagnostics {
  std::uint64_t degenerate_triangles = 0;
};

// Throws InputError prefixed by `where` (file and mesh/primitive/accessor) for NaN/Inf data,
// mismatched attribute counts or out-of-range indices.
void finalize_mesh(Mesh& mesh, const std::string& where, LoadDiagnostics& diagnostics);

}  // namespace lantern
