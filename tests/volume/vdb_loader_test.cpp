// Bad volume input is one InputError naming the level entry, the .vdb file and the problem:
// every bad file here is written through OpenVDB (or is a good one truncated or overwritten).
#include <gtest/gtest.h>

#include <fstream>

#include "engine/level/level_loader.h"
#include "runtime/volume/vdb_reader.h"
#include "runtime/volume/volume_set.h"
#include "tests/volume/vdb_fixtures.h"

namespace lantern::test {
namespace {

namespace fs = std::filesystem;

Volume volume_of(const fs::path& file, const std::string& grid = "density") {
  Volume v;
  v.file = file;
  v.grid = grid;
  v.where = "test.json: /volumes/0";
  return v;
}

std::string load_error(const Volume& v) {
  return input_error([&] { runtime::load_volume_grid(v); });
}

void expect_contains(const std::string& message, const std::string& part) {
  EXPECT_NE(message.find(part), std::string::npos) << "'" << part << "' not in: " << message;
}

TEST(VdbLoader, GoodFileLoads) {
  const fs::path file = volume_scratch("good.vdb");
  write_vdb(file, {cube_grid("density", 4, 0.5f)});
  const runtime::VolumeGrid g = runtime::load_volume_grid(volume_of(file));
  EXPECT_EQ(g.active_voxels, 64u);
  EXPECT_FLOAT_EQ(g.max_value, 0.5f);
  EXPECT_EQ(g.active_min, glm::ivec3(0));
  EXPECT_EQ(g.active_max, glm::ivec3(3));
}

TEST(VdbLoader, MissingFile) {
  const std::string e = load_error(volume_of(volume_scratch("nowhere.vdb")));
  expect_contains(e, "test.json: /volumes/0");
  expect_contains(e, "nowhere.vdb");
  expect_contains(e, "not found");
}

TEST(VdbLoader, TruncatedFile) {
  const fs::path good = volume_scratch("to_truncate.vdb");
  write_vdb(good, {cube_grid("density", 16, 1.0f)});
  const auto size = fs::file_size(good);
  for (std::uintmax_t keep : {std::uintmax_t{0}, std::uintmax_t{20}, size / 2, size - 8}) {
    const fs::path cut = volume_scratch("truncated.vdb");
    fs::copy_file(good, cut, fs::copy_options::overwrite_existing);
    fs::resize_file(cut, keep);
    const std::string e = load_error(volume_of(cut));
    SCOPED_TRACE(keep);
    expect_contains(e, "truncated.vdb");
    expect_contains(e, "test.json: /volumes/0");
  }
}

TEST(VdbLoader, CorruptFile) {
  const fs::path text = volume_scratch("text.vdb");
  write_text_file(text, "this is not an OpenVDB file, just text that ends here\n");
  expect_contains(load_error(volume_of(text)), "cannot read the OpenVDB file");

  const fs::path good = volume_scratch("to_corrupt.vdb");
  write_vdb(good, {cube_grid("density", 16, 1.0f)});
  std::fstream f(good, std::ios::in | std::ios::out | std::ios::binary);
  f.seekp(static_cast<std::streamoff>(fs::file_size(good) / 3));
  const std::string garbage(64, '\xA5');
  f.write(garbage.data(), static_cast<std::streamsize>(garbage.size()));
  f.close();
  // Either OpenVDB notices (a read error) or the values it decodes are refused; never a crash.
  expect_contains(load_error(volume_of(good)), "to_corrupt.vdb");
}

TEST(VdbLoader, MissingGridListsTheGridsPresent) {
  const fs::path file = volume_scratch("named.vdb");
  write_vdb(file, {cube_grid("smoke", 2, 1.0f), cube_grid("temperature", 2, 1.0f)});
  const std::string e = load_error(volume_of(file, "density"));
  expect_contains(e, "no grid named 'density'");
  expect_contains(e, "'smoke'");
  expect_contains(e, "'temperature'");
}

TEST(VdbLoader, GridThatIsNotFloat) {
  const fs::path file = volume_scratch("vector.vdb");
  openvdb::Vec3SGrid::Ptr grid = openvdb::Vec3SGrid::create();
  grid->setName("density");
  grid->tree().setValue(openvdb::Coord(1, 2, 3), openvdb::Vec3s(1.0f, 0.0f, 0.0f));
  write_vdb(file, {grid});
  const std::string e = load_error(volume_of(file));
  expect_contains(e, "not float");
  expect_contains(e, "vec3s");
}

TEST(VdbLoader, NonFiniteAndNegativeDensityNameTheVoxel) {
  struct Case {
    float value;
    const char* says;
  };
  for (const Case& c : {Case{std::nanf(""), "is NaN"}, Case{INFINITY, "is infinite"},
                        Case{-0.25f, "negative density -0.25"}}) {
    const fs::path file = volume_scratch("bad_value.vdb");
    openvdb::FloatGrid::Ptr grid = cube_grid("density", 4, 1.0f);
    grid->tree().setValue(openvdb::Coord(2, 1, 3), c.value);
    write_vdb(file, {grid});
    const std::string e = load_error(volume_of(file));
    expect_contains(e, c.says);
    expect_contains(e, "voxel (2, 1, 3)");
  }
}

TEST(VdbLoader, AbsurdVoxelCountsAreCapped) {
  const fs::path file = volume_scratch("huge.vdb");
  openvdb::FloatGrid::Ptr grid = openvdb::FloatGrid::create(0.0f);
  grid->setName("density");
  grid->fill(openvdb::CoordBBox(openvdb::Coord(0), openvdb::Coord(4095)), 1.0f, true);  // tiles
  write_vdb(file, {grid});
  expect_contains(load_error(volume_of(file)),
                  "more than the limit of " + std::to_string(runtime::kMaxVolumeActiveVoxels));

  const fs::path sparse = volume_scratch("sparse.vdb");
  openvdb::FloatGrid::Ptr far = openvdb::FloatGrid::create(0.0f);
  far->setName("density");
  far->tree().setValue(openvdb::Coord(0), 1.0f);
  far->tree().setValue(openvdb::Coord(4000, 4000, 4000), 1.0f);
  write_vdb(sparse, {far});
  expect_contains(load_error(volume_of(sparse)),
                  "limit of " + std::to_string(runtime::kMaxVolumeCells) + " cells");
}

TEST(VdbLoader, NonAffineTransformIsRefused) {
  const fs::path file = volume_scratch("frustum.vdb");
  openvdb::FloatGrid::Ptr grid = cube_grid("density", 4, 1.0f);
  grid->setTransform(openvdb::math::Transform::createFrustumTransform(
      openvdb::BBoxd(openvdb::Vec3d(0.0), openvdb::Vec3d(4.0)), 0.5, 2.0, 1.0));
  write_vdb(file, {grid});
  expect_contains(load_error(volume_of(file)), "non-affine transform");
}

TEST(VdbLoader, AbsurdExtinctionIsRefused) {
  const fs::path file = volume_scratch("dense.vdb");
  write_vdb(file, {cube_grid("density", 2, 1.0e4f)});
  Volume v = volume_of(file);
  v.density_scale = 1.0e6f;  // the level's limit; times the grid's 1e4: 1e10 1/m
  expect_contains(load_error(v), "is absurd");
}

// The level entry's own checks (engine/level/json_level_volumes.cpp), through load_level.
std::string level_error(const std::string& entry) {
  const fs::path vdb = volume_scratch("entry.vdb");
  if (!fs::exists(vdb)) write_vdb(vdb, {cube_grid("density", 2, 1.0f)});
  const fs::path level = volume_scratch("entry_level.json");
  write_text_file(level, "{\"volumes\": [" + entry + "]}");
  return input_error([&] { load_level(level); });
}

TEST(VdbLoader, AbsurdCoefficientsInTheLevel) {
  expect_contains(level_error(R"({"file": "entry.vdb", "scattering": [1, -1, 1]})"),
                  "/volumes/0/scattering: negative coefficient");
  expect_contains(level_error(R"({"file": "entry.vdb", "absorption": [1, 1, 2e7]})"),
                  "/volumes/0/absorption: coefficient");
  expect_contains(level_error(R"({"file": "entry.vdb", "anisotropy": 1.0})"),
                  "/volumes/0/anisotropy: Henyey-Greenstein g = 1 is outside (-1, 1)");
  expect_contains(level_error(R"({"file": "entry.vdb", "anisotropy": -1.5})"),
                  "/volumes/0/anisotropy");
  expect_contains(level_error(R"({"file": "entry.vdb", "density_scale": 1e7})"),
                  "/volumes/0/density_scale: density_scale 10000000 is absurd (limit 1000000)");
  expect_contains(level_error(R"({"file": "entry.vdb", "density_scale": -1})"),
                  "negative density_scale");
  expect_contains(level_error(R"({"file": "missing.vdb"})"),
                  "/volumes/0/file: file 'missing.vdb' not found");
  expect_contains(level_error(R"({"file": "entry.vdb", "generate": {"type": "constant"}})"),
                  "exactly one of 'file'");
  expect_contains(level_error(R"({"generate": {"type": "clouds"}})"),
                  "unknown volume generator 'clouds' (constant, smoke_plume, ground_fog)");
  expect_contains(
      level_error(
          R"({"generate": {"type": "constant", "size": [100, 100, 100], "voxel_size": 0.1}})"),
      "exceeds the limit of " + std::to_string(kMaxGeneratedVolumeVoxels));
  expect_contains(level_error(R"({"file": "entry.vdb", "behaviour": {"type": "flicker"}})"),
                  "volumes do not emit");
  expect_contains(level_error(R"({"file": "entry.vdb", "colour": [1, 1, 1]})"),
                  "unknown key 'colour'");
}

}  // namespace
}  // namespace lantern::test
