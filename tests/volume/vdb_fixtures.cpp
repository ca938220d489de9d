// Volume test helpers (vdb_fixtures.h).
#include "tests/volume/vdb_fixtures.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>

#include "engine/core/error.h"

namespace lantern::test {

namespace {

// A per-process directory, removed when the process exits.
struct ScratchDir {
  std::filesystem::path path = std::filesystem::temp_directory_path() /
                               ("lantern-volume-test-" + std::to_string(::getpid()));
  ScratchDir() { std::filesystem::create_directories(path); }
  ~ScratchDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path, ignored);
  }
};

}  // namespace

std::filesystem::path volume_scratch(const std::string& name) {
  static const ScratchDir dir;
  return dir.path / name;
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
