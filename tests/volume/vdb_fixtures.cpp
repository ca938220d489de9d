// Volume test helpers (vdb_fixtures.h).
#include "tests/volume/vdb_fixtures.h"

#include <gtest/gtest.h>

#include <fstream>

#include "engine/core/error.h"
#include "tests/runtime/scratch_dir.h"

namespace lantern::test {

std::filesystem::path volume_scratch(const std::string& name) {
  return process_scratch_dir() / name;
}

void write_text_file(const std::filesystem::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << text;
}

void write_vdb(const std::filesystem::path& path, const openvdb::GridPtrVec& grids) {
  openvdb::initialize();
  openvdb::io::File file(path.string());
  file.write(grids);
  file.close();
}

openvdb::FloatGrid::Ptr cube_grid(const std::string& name, int n, float value) {
  openvdb::initialize();
  openvdb::FloatGrid::Ptr grid = openvdb::FloatGrid::create(0.0f);
  grid->setName(name);
  openvdb::FloatGrid::Accessor acc = grid->getAccessor();
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) acc.setValue(openvdb::Coord(i, j, k), value);
  return grid;
}

std::string input_error(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "expected InputError, got: " << e.what();
    return {};
  }
  ADD_FAILURE() << "expected InputError, nothing was thrown";
  return {};
}

}  // namespace lantern::test
