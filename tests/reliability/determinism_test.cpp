// Determinism: the same level, seed and settings give bitwise-identical EXR frames across two runs
// in one process and across World scheduler thread counts (1 vs 2), for every implemented
// integrator; a different seed gives different frames (so the comparison can fail).
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cstring>
#include <fstream>

#include "engine/core/error.h"
#include "engine/level/level_loader.h"
#include "runtime/gpu/shader_library.h"
#include "runtime/image/image_io.h"
#include "tests/reliability/frame_loop.h"
#include "tests/runtime/gpu_test_support.h"

namespace lantern {
namespace {

namespace fs = std::filesystem;
constexpr std::uint32_t kFrames = 6;

class DeterminismTest : public runtime::test::GpuTest,
                        public ::testing::WithParamInterface<std::string> {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / fmt::format("lantern-determinism-{}-{}", ::getpid(),
                                                   GetParam());
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ignored;
    fs::remove_all(dir_, ignored);
    runtime::test::GpuTest::TearDown();
  }

  // Renders kFrames frames of cornell_lights (its lights flicker and move) and writes them as EXR
  // files under dir_/run; returns the file paths.
  std::vector<fs::path> run(const std::string& run, std::uint32_t seed, unsigned threads) {
    reliability::LoopOptions o;
    o.integrator.name = GetParam();
    o.seed = seed;
    o.world_threads = threads;
    reliability::FrameLoop loop(device, shaders_, level_, o);
    std::vector<fs::path> files;
    fs::create_directories(dir_ / run);
    for (std::uint32_t f = 0; f < kFrames; ++f) {
      const runtime::ImageRGBA32F image = loop.frame();
      EXPECT_EQ(image.count_non_finite(), 0u) << run << " frame " << f;
      files.push_back(dir_ / run / fmt::format("frame_{:04}.exr", f));
      runtime::write_exr(files.back(), image);
    }
    return files;
  }

  static std::string bytes(const fs::path& file) {
    std::ifstream in(file, std::ios::binary | std::ios::ate);
    std::string data(static_cast<std::size_t>(std::max<std::streamoff>(in.tellg(), 0)), '\0');
    in.seekg(0);
    in.read(data.data(), static_cast<std::streamsize>(data.size()));
    return data;
  }

  static std::size_t identical_files(const std::vector<fs::path>& a,
                                     const std::vector<fs::path>& b) {
    std::size_t same = 0;
    for (std::size_t i = 0; i < a.size() && i < b.size(); ++i) {
      const std::string x = bytes(a[i]), y = bytes(b[i]);
      EXPECT_FALSE(x.empty());
      same += !x.empty() && x == y ? 1 : 0;
    }
    return same;
  }

  runtime::ShaderLibrary shaders_;
  std::shared_ptr<const Level> level_ =
      std::make_shared<const Level>(load_level_argument("cornell_lights"));
  fs::path dir_;
};

TEST_P(DeterminismTest, TwoRunsWriteIdenticalExrFrames) {
  const auto a = run("a", 7, 1);
  const auto b = run("b", 7, 1);
  EXPECT_EQ(identical_files(a, b), kFrames);
}

TEST_P(DeterminismTest, WorldThreadCountsOneAndTwoWriteIdenticalExrFrames) {
  const auto a = run("t1", 7, 1);
  const auto b = run("t2", 7, 2);
  EXPECT_EQ(identical_files(a, b), kFrames);
}

TEST_P(DeterminismTest, AnotherSeedChangesTheFrames) {
  const auto a = run("s7", 7, 1);
  const auto b = run("s8", 8, 1);
  EXPECT_LT(identical_files(a, b), kFrames) << "the seed does not reach the frames, so equal "
                                               "frames above would prove nothing";
}

INSTANTIATE_TEST_SUITE_P(Integrators, DeterminismTest,
                         ::testing::Values("baseline", "restir"),
                         [](const auto& param_info) {
                           return param_info.param;
                         });

}  // namespace
}  // namespace lantern
