// OpenVDB file -> VolumeGrid, with every check of vdb_reader.h.
#include "runtime/volume/vdb_reader.h"

#include <fmt/format.h>
#include <openvdb/io/Stream.h>
#include <openvdb/openvdb.h>

#include <cmath>
#include <fstream>
#include <mutex>
#include <streambuf>
#include <vector>

#include "engine/core/error.h"
#include "engine/scene/finite.h"

namespace lantern::runtime {

void initialize_openvdb() {
  static std::once_flag once;
  std::call_once(once, [] { openvdb::initialize(); });
}

namespace {

std::string names_of(const openvdb::io::File& file) {
  std::string out;
  for (auto it = file.beginName(); it != file.endName(); ++it)
    out += (out.empty() ? "'" : ", '") + *it + "'";
  return out.empty() ? "none" : out;
}

// A file-supplied statistic ("file_voxel_count", written by OpenVDB) as an early cap check,
// before the tree is read; absent or odd metadata is ignored (the real count is checked later).
std::uint64_t metadata_voxel_count(const openvdb::GridBase& meta) {
  const auto value = meta.getMetadata<openvdb::Int64Metadata>("file_voxel_count");
  return value && value->value() > 0 ? static_cast<std::uint64_t>(value->value()) : 0;
}

glm::mat4 to_glm(const openvdb::math::Mat4d& m) {
  // OpenVDB multiplies row vectors (p' = p M, translation in row 3); glm columns are its rows.
  glm::mat4 out;
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) out[c][r] = static_cast<float>(m(c, r));
  return out;
}

// A file's bytes followed by zeros without end. OpenVDB reads the voxels through this: past the
// end of a truncated file it reads zeros instead of failing (a failed std::istream leaves the
// variables it reads unset, and OpenVDB 10 then allocates garbage sizes from them), and
// past_end() tells the reader that the data ran out.
class ZeroExtendedBuffer : public std::streambuf {
 public:
  explicit ZeroExtendedBuffer(std::vector<char> bytes)
      : bytes_(std::move(bytes)), zeros_(4096, '\0') {
    show(0);
  }
  bool past_end() const { return past_end_; }

 protected:
  int_type underflow() override {
    const std::uint64_t at = position();
    if (at >= bytes_.size()) past_end_ = true;
    show(at);
    return traits_type::to_int_type(*gptr());
  }
  pos_type seekoff(off_type off, std::ios_base::seekdir dir, std::ios_base::openmode) override {
    const std::int64_t from = dir == std::ios_base::beg   ? 0
                              : dir == std::ios_base::end ? std::int64_t(bytes_.size())
                                                          : std::int64_t(position());
    if (from + off < 0) return pos_type(off_type(-1));
    show(std::uint64_t(from + off));
    return pos_type(off_type(from + off));
  }
  pos_type seekpos(pos_type pos, std::ios_base::openmode mode) override {
    return seekoff(off_type(pos), std::ios_base::beg, mode);
  }

 private:
  std::uint64_t position() const { return base_ + std::uint64_t(gptr() - eback()); }
  // Makes the get area start at `at`: the rest of the file, or a window of zeros beyond it.
  void show(std::uint64_t at) {
    if (at < bytes_.size()) {
      base_ = 0;
      setg(bytes_.data(), bytes_.data() + at, bytes_.data() + bytes_.size());
    } else {
      base_ = at;
      setg(zeros_.data(), zeros_.data(), zeros_.data() + zeros_.size());
    }
  }

  std::vector<char> bytes_;
  std::vector<char> zeros_;
  std::uint64_t base_ = 0;
  bool past_end_ = false;
};

// Larger files are refused before they are read into memory (the caps allow ~128 MiB of values).
constexpr std::uintmax_t kMaxVdbFileBytes = std::uintmax_t{1} << 30;

class Reader {
 public:
  Reader(const std::filesystem::path& file, const std::string& grid, const std::string& where)
      : file_(file), grid_name_(grid), where_(where) {}

  [[noreturn]] void fail(const std::string& problem) const {
    throw InputError(fmt::format("{}: {}: {}", where_, file_.string(), problem));
  }

  // Names, types and the voxel counts the file claims, from the headers alone (no voxels read):
  // the requested grid must exist and be float; no grid may claim more voxels than the cap (the
  // stream below reads every grid of the file).
  void check_metadata() {
    openvdb::io::File file(file_.string());
    file.open(/*delayLoad=*/false);
    if (!file.hasGrid(grid_name_))
      fail(fmt::format("no grid named '{}' (grids in the file: {})", grid_name_, names_of(file)));
    const openvdb::GridPtrVecPtr metas = file.readAllGridMetadata();
    for (const openvdb::GridBase::Ptr& meta : metas ? *metas : openvdb::GridPtrVec{}) {
      if (!meta) continue;
      if (meta->getName() == grid_name_ && !meta->isType<openvdb::FloatGrid>())
        fail(fmt::format("grid '{}' holds {} values, not float (a float density grid is needed)",
                         grid_name_, meta->valueType()));
      if (const std::uint64_t claimed = metadata_voxel_count(*meta);
          claimed > kMaxVolumeActiveVoxels)
        fail(fmt::format("grid '{}' has {} active voxels, more than the limit of {}",
                         meta->getName(), claimed, kMaxVolumeActiveVoxels));
    }
    file.close();
  }

  VolumeGrid read() {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(file_, ec)) {
      const bool missing = !ec || ec == std::errc::no_such_file_or_directory ||
                           ec == std::errc::not_a_directory;
      fail(missing ? "volume file not found"
                   : fmt::format("volume file cannot be read: {}", ec.message()));
    }
    initialize_openvdb();
    openvdb::FloatGrid::Ptr grid;
    try {
      check_metadata();
      // The voxels through io::Stream over the zero-extended bytes: unlike io::File, whose reads
      // past the end of a truncated file go unnoticed, the buffer tells (see ZeroExtendedBuffer).
      const std::uintmax_t size = std::filesystem::file_size(file_);
      if (size > kMaxVdbFileBytes)
        fail(fmt::format("the file has {} bytes, more than the limit of {}", size,
                         kMaxVdbFileBytes));
      std::vector<char> bytes(size);
      std::ifstream in(file_, std::ios::binary);
      if (!in.read(bytes.data(), std::streamsize(size))) fail("cannot read the volume file");
      ZeroExtendedBuffer buffer(std::move(bytes));
      std::istream zero_extended(&buffer);
      openvdb::io::Stream stream(zero_extended, /*delayLoad=*/false);
      const openvdb::GridPtrVecPtr grids = stream.getGrids();
      if (buffer.past_end() || zero_extended.fail())
        fail("the OpenVDB file is truncated (its data ends before the grids do)");
      for (const openvdb::GridBase::Ptr& g : grids ? *grids : openvdb::GridPtrVec{})
        if (g && g->getName() == grid_name_) grid = openvdb::gridPtrCast<openvdb::FloatGrid>(g);
    } catch (const InputError&) {
      throw;
    } catch (const std::exception& e) {
      // openvdb::IoError and friends, and what a corrupt stream makes the reader throw.
      fail(fmt::format("cannot read the OpenVDB file (truncated or corrupt?): {}", e.what()));
    }
    if (!grid) fail(fmt::format("grid '{}' could not be read as a float grid", grid_name_));
    return convert(*grid);
  }

 private:
  VolumeGrid convert(const openvdb::FloatGrid& grid) {
    VolumeGrid out;
    out.file = file_;
    out.grid_name = grid_name_;
    const openvdb::math::Transform& xf = grid.transform();
    if (!xf.isLinear())
      fail(
          fmt::format("grid '{}' has a non-affine transform ({}); only affine index-to-world "
                      "transforms are supported",
                      grid_name_, xf.mapType()));
    out.index_to_world = to_glm(xf.baseMap()->getAffineMap()->getMat4());
    const float det = glm::determinant(out.index_to_world);
    if (!all_finite(out.index_to_world) || !(std::abs(det) > 1e-30f) || !std::isfinite(det))
      fail(fmt::format("grid '{}' has a singular or non-finite transform", grid_name_));

    out.active_voxels = grid.activeVoxelCount();
    if (out.active_voxels > kMaxVolumeActiveVoxels)
      fail(fmt::format("grid '{}' has {} active voxels, more than the limit of {}", grid_name_,
                       out.active_voxels, kMaxVolumeActiveVoxels));
    if (out.active_voxels == 0) return VolumeGridBuilder({0, 0, 0}, {-1, -1, -1}).finish(out);
    const openvdb::CoordBBox box = grid.evalActiveVoxelBoundingBox();
    out.active_min = glm::ivec3(box.min().x(), box.min().y(), box.min().z());
    out.active_max = glm::ivec3(box.max().x(), box.max().y(), box.max().z());
    // Far from OpenVDB's +-2^31 index range limits and exact in the shaders' float coordinates.
    constexpr int kMaxIndex = 1 << 23;
    if (glm::any(glm::lessThan(out.active_min, glm::ivec3(-kMaxIndex))) ||
        glm::any(glm::greaterThan(out.active_max, glm::ivec3(kMaxIndex))))
      fail(fmt::format("grid '{}' has active voxels beyond index +-{}", grid_name_, kMaxIndex));
    const std::uint64_t cells = volume_cells_for(out.active_min, out.active_max);
    if (cells > kMaxVolumeCells)
      fail(
          fmt::format("grid '{}' spans {} x {} x {} voxels ({} cells of 8^3), more than the "
                      "limit of {} cells",
                      grid_name_, out.active_max.x - out.active_min.x + 1,
                      out.active_max.y - out.active_min.y + 1,
                      out.active_max.z - out.active_min.z + 1, cells, kMaxVolumeCells));

    VolumeGridBuilder builder(out.active_min, out.active_max);
    auto check = [&](float v, const openvdb::Coord& c) {
      if (!std::isfinite(v))
        fail(fmt::format("grid '{}' voxel ({}, {}, {}) is {}", grid_name_, c.x(), c.y(), c.z(),
                         std::isnan(v) ? "NaN" : "infinite"));
      if (v < 0.0f)
        fail(fmt::format("grid '{}' voxel ({}, {}, {}) has negative density {}", grid_name_, c.x(),
                         c.y(), c.z(), v));
      out.max_value = std::max(out.max_value, v);
    };
    for (auto it = grid.cbeginValueOn(); it; ++it) {
      const float v = *it;
      if (it.isVoxelValue()) {
        check(v, it.getCoord());
        builder.set(glm::ivec3(it.getCoord().x(), it.getCoord().y(), it.getCoord().z()), v);
        continue;
      }
      openvdb::CoordBBox tile;  // an active tile: one value over a box of voxels
      it.getBoundingBox(tile);
      check(v, tile.min());
      for (int z = tile.min().z(); z <= tile.max().z(); ++z)
        for (int y = tile.min().y(); y <= tile.max().y(); ++y)
          for (int x = tile.min().x(); x <= tile.max().x(); ++x) builder.set({x, y, z}, v);
    }
    return builder.finish(std::move(out));
  }

  const std::filesystem::path& file_;
  const std::string& grid_name_;
  const std::string& where_;
};

}  // namespace

VolumeGrid read_vdb_grid(const std::filesystem::path& file, const std::string& grid_name,
                         const std::string& where) {
  return Reader(file, grid_name, where).read();
}

}  // namespace lantern::runtime
