// Helpers for the volume tests: a scratch directory, .vdb files written through OpenVDB, JSON
// levels with a volumes section, and the InputError of a call.
#pragma once

#include <openvdb/openvdb.h>

#include <filesystem>
#include <functional>
#include <string>

namespace lantern::test {

std::filesystem::path volume_scratch(const std::string& name);
void write_text_file(const std::filesystem::path& path, const std::string& text);
// Writes `grids` to `path` through OpenVDB (initialises the library first).
void write_vdb(const std::filesystem::path& path, const openvdb::GridPtrVec& grids);
// A float grid named `name` with `value` at each voxel (i, j, k) of [0, n)^3, unit voxels.
openvdb::FloatGrid::Ptr cube_grid(const std::string& name, int n, float value);
// The message of the InputError `f` throws ("" and a test failure when it throws none).
std::string input_error(const std::function<void()>& f);

}  // namespace lantern::test
