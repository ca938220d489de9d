// The vdb fuzz target (fuzz_targets.h): input bytes -> scratch .vdb -> runtime::read_vdb_grid.
#include <unistd.h>

#include <fstream>
#include <string>

#include "engine/core/error.h"
#include "runtime/volume/vdb_reader.h"
#include "tests/fuzz/fuzz_targets.h"

namespace lantern::fuzz {

int vdb(const std::uint8_t* data, std::size_t size) {
  static const std::filesystem::path file =
      std::filesystem::temp_directory_path() /
      ("lantern-fuzz-vdb-" + std::to_string(::getpid()) + ".vdb");
  {
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  try {
    const runtime::VolumeGrid grid = runtime::read_vdb_grid(file, "density", "fuzz");
    (void)grid;
  } catch (const InputError&) {
    // The expected outcome for bad input.
  }
  std::error_code ignored;
  std::filesystem::remove(file, ignored);
  return 0;
}

}  // namespace lantern::fuzz
