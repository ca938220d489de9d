// A directory of this test process's own under the system's temporary directory, removed when
// the process exits. ctest runs test processes side by side, so what they write must not share a
// path: with one shared level file a fixture read another's half-written JSON ("malformed JSON
// ... unexpected end of input", DenoiseGpuTest under CI's -j2).
#pragma once

#include <unistd.h>

#include <filesystem>
#include <string>
#include <system_error>

namespace lantern::test {

inline const std::filesystem::path& process_scratch_dir() {
  struct Dir {
    std::filesystem::path path =
        std::filesystem::temp_directory_path() / ("lantern_test_" + std::to_string(::getpid()));
    Dir() { std::filesystem::create_directories(path); }
    ~Dir() {
      std::error_code ignored;
      std::filesystem::remove_all(path, ignored);
    }
  };
  static const Dir dir;
  return dir.path;
}

}  // namespace lantern::test
