// Replays every seed-corpus input and every regression input (inputs that once crashed, hung or
// allocated absurdly in a fuzz run) through the fuzz targets in the normal build, so CI checks
// them without clang/libFuzzer. Passing = no crash and no exception other than InputError.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <iterator>
#include <vector>

#include "tests/fuzz/fuzz_targets.h"

namespace {

namespace fs = std::filesystem;
const fs::path kFuzzDir = LANTERN_FUZZ_DIR;

std::vector<fs::path> inputs(const std::string& target) {
  std::vector<fs::path> files;
  for (const char* set : {"corpus", "regressions"}) {
    const fs::path dir = kFuzzDir / set / target;
    if (!fs::is_directory(dir)) continue;
    for (const auto& e : fs::directory_iterator(dir))
      if (e.is_regular_file() && e.path().filename().string()[0] != '.') files.push_back(e.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

std::vector<std::uint8_t> bytes_of(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

class FuzzReplay : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { lantern::fuzz::init(LANTERN_FUZZ_ASSETS); }
  static void TearDownTestSuite() { lantern::fuzz::cleanup(); }

  template <class Target>
  static void replay(const std::string& target, Target&& run) {
    const std::vector<fs::path> files = inputs(target);
    ASSERT_GE(files.size(), 3u) << "seed corpus for " << target << " is missing";
    for (const fs::path& f : files) {
      SCOPED_TRACE(f.string());
      const std::vector<std::uint8_t> data = bytes_of(f);
      EXPECT_NO_THROW(run(data.data(), data.size()));
    }
  }
};

TEST_F(FuzzReplay, LevelJson) {
  replay("level_json", lantern::fuzz::level_json);
}
TEST_F(FuzzReplay, Gltf) {
  replay("gltf", lantern::fuzz::gltf);
}
TEST_F(FuzzReplay, Image) {
  replay("image", lantern::fuzz::image);
}
TEST_F(FuzzReplay, Vdb) {
  replay("vdb", lantern::fuzz::vdb);
}

}  // namespace
