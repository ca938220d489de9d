// Procedural .vdb files: density functions, the OpenVDB grid and file, the cache (see header).
#include "runtime/volume/volume_generator.h"

#include <fmt/format.h>
#include <openvdb/openvdb.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <cstring>

#include "engine/core/error.h"
#include "runtime/volume/vdb_reader.h"

namespace lantern::runtime {
namespace {

// Bump when any density function changes: cached files of the old version are then not reused.
constexpr std::uint32_t kGeneratorVersion = 2;

std::uint64_t mix64(std::uint64_t z) {  // SplitMix64's finaliser: a good 64-bit hash
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

// Uniform in [0, 1) at an integer lattice point.
float lattice(std::int64_t x, std::int64_t y, std::int64_t z, std::uint64_t seed) {
  std::uint64_t h = mix64(seed + 0x9E3779B97F4A7C15ull);
  h = mix64(h ^ static_cast<std::uint64_t>(x));
  h = mix64(h ^ static_cast<std::uint64_t>(y));
  h = mix64(h ^ static_cast<std::uint64_t>(z));
  return static_cast<float>(h >> 40) * (1.0f / 16777216.0f);
}

// Value noise in [0, 1): smoothstep-interpolated lattice values.
float value_noise(glm::vec3 p, std::uint64_t seed) {
  const glm::vec3 b = glm::floor(p);
  const glm::vec3 f = p - b;
  const glm::vec3 w = f * f * (3.0f - 2.0f * f);
  const auto x = static_cast<std::int64_t>(b.x), y = static_cast<std::int64_t>(b.y),
             z = static_cast<std::int64_t>(b.z);
  float c[2][2][2];
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 2; ++i) c[k][j][i] = lattice(x + i, y + j, z + k, seed);
  auto lerp = [](float a, float bb, float t) { return a + (bb - a) * t; };
  const float y0 = lerp(lerp(c[0][0][0], c[0][0][1], w.x), lerp(c[0][1][0], c[0][1][1], w.x), w.y);
  const float y1 = lerp(lerp(c[1][0][0], c[1][0][1], w.x), lerp(c[1][1][0], c[1][1][1], w.x), w.y);
  return lerp(y0, y1, w.z);
}

// Four octaves of value noise, in [0, 1).
float fbm(glm::vec3 p, std::uint64_t seed) {
  float sum = 0.0f, amplitude = 0.5f, norm = 0.0f;
  for (int octave = 0; octave < 4; ++octave) {
    sum += amplitude * value_noise(p, seed + static_cast<std::uint64_t>(octave));
    norm += amplitude;
    amplitude *= 0.5f;
    p *= 2.03f;
  }
  return sum / norm;
}

float smoothstep(float e0, float e1, float x) {
  const float t = std::clamp((x - e0) / (e1 - e0), 0.0f, 1.0f);
  return t * t * (3.0f - 2.0f * t);
}

// Density at local point p (metres; x, z centred, y from the floor) of a box of `size`.
float density(const VolumeGenerator& g, glm::vec3 p) {
  const glm::vec3 s = g.size;
  switch (g.type) {
    case VolumeGeneratorType::Constant:
      return 1.0f;
    case VolumeGeneratorType::GroundFog: {
      const float height = std::exp(-p.y / (s.y / 3.0f));
      const float edge = smoothstep(0.0f, 0.12f * s.x, 0.5f * s.x - std::abs(p.x)) *
                         smoothstep(0.0f, 0.12f * s.z, 0.5f * s.z - std::abs(p.z)) *
                         smoothstep(0.0f, 0.1f * s.y, s.y - p.y);
      const float noise = fbm(p / (0.25f * std::max(s.x, s.z)), g.seed);
      return height * edge * (0.35f + 0.65f * noise);
    }
    case VolumeGeneratorType::SmokePlume: {
      const float h = std::clamp(p.y / s.y, 0.0f, 1.0f);
      const float phase = lattice(0, 0, 0, g.seed) * 6.2831853f;
      const glm::vec2 centre = 0.18f * glm::vec2(s.x, s.z) * h *
                               glm::vec2(std::sin(3.0f * h + phase), std::cos(2.3f * h + phase));
      const float radius = (0.12f + 0.5f * h) * 0.5f * std::min(s.x, s.z);
      const float r = glm::length(glm::vec2(p.x, p.z) - centre) / radius;
      const float noise =
          fbm(p / (0.2f * std::min(s.x, s.z)) + glm::vec3(0.0f, -2.0f * h, 0.0f), g.seed);
      const float core = std::max(0.0f, 1.0f - r * (0.7f + 0.6f * noise));
      return core * std::sqrt(1.0f - h) * (0.4f + 0.6f * noise);
    }
  }
  return 0.0f;
}

std::uint64_t fnv1a(std::uint64_t h, const void* data, std::size_t size) {
  const auto* bytes = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < size; ++i) h = (h ^ bytes[i]) * 0x100000001B3ull;
  return h;
}

}  // namespace

std::filesystem::path volume_cache_dir() {
  if (const char* env = std::getenv("LANTERN_CACHE_DIR"); env && *env)
    return std::filesystem::path(env) / "volumes";
#ifdef LANTERN_SHADER_DIR
  return std::filesystem::path(LANTERN_SHADER_DIR).parent_path() / "volume-cache";
#else
  return std::filesystem::temp_directory_path() / "lantern-volume-cache";
#endif
}

std::string generated_volume_name(const VolumeGenerator& g) {
  std::uint64_t h = 0xCBF29CE484222325ull;
  const auto type = static_cast<std::uint32_t>(g.type);
  h = fnv1a(h, &kGeneratorVersion, sizeof kGeneratorVersion);
  h = fnv1a(h, &type, sizeof type);
  h = fnv1a(h, &g.seed, sizeof g.seed);
  h = fnv1a(h, &g.size, sizeof g.size);
  h = fnv1a(h, &g.voxel_size, sizeof g.voxel_size);
  return fmt::format("{}-{:016x}.vdb", volume_generator_name(g.type), h);
}

void write_generated_volume(const VolumeGenerator& g, const std::filesystem::path& file) {
  const glm::uvec3 n = g.voxel_counts();
  if (std::uint64_t{n.x} * n.y * n.z > kMaxGeneratedVolumeVoxels)
    throw InputError(fmt::format("volume generator {}: {} x {} x {} voxels exceeds the limit of {}",
                                 volume_generator_name(g.type), n.x, n.y, n.z,
                                 kMaxGeneratedVolumeVoxels));
  initialize_openvdb();
  openvdb::FloatGrid::Ptr grid = openvdb::FloatGrid::create(0.0f);
  grid->setName("density");
  grid->setGridClass(openvdb::GRID_FOG_VOLUME);
  // Voxel (i, j, k) has its centre at corner + (i + 1/2, j + 1/2, k + 1/2) * voxel_size.
  const double vs = g.voxel_size;
  const glm::dvec3 corner(-0.5 * n.x * vs, 0.0, -0.5 * n.z * vs);
  openvdb::math::Transform::Ptr xf = openvdb::math::Transform::createLinearTransform(vs);
  xf->postTranslate(openvdb::Vec3d(corner.x + 0.5 * vs, corner.y + 0.5 * vs, corner.z + 0.5 * vs));
  grid->setTransform(xf);
  openvdb::FloatGrid::Accessor acc = grid->getAccessor();
  for (unsigned k = 0; k < n.z; ++k)
    for (unsigned j = 0; j < n.y; ++j)
      for (unsigned i = 0; i < n.x; ++i) {
        const glm::vec3 p(corner + (glm::dvec3(i, j, k) + 0.5) * vs);
        const float d = density(g, p);
        if (d > 1e-4f) acc.setValue(openvdb::Coord(int(i), int(j), int(k)), std::min(d, 1.0f));
      }
  grid->pruneGrid();  // constant regions become tiles (the reader expands them)
  grid->insertMeta("lantern_generator", openvdb::StringMetadata(volume_generator_name(g.type)));
  grid->insertMeta("lantern_seed", openvdb::Int64Metadata(static_cast<std::int64_t>(g.seed)));

  std::error_code ec;
  std::filesystem::create_directories(file.parent_path(), ec);
  static std::atomic<std::uint32_t> writes{0};  // distinct temporary names across threads too
  const std::filesystem::path temp =
      file.parent_path() /
      fmt::format(".{}.{}.{}.tmp", file.filename().string(), ::getpid(), writes++);
  try {
    openvdb::io::File out(temp.string());
    out.write({grid});
    out.close();
  } catch (const std::exception& e) {
    std::filesystem::remove(temp, ec);
    throw RuntimeError(
        fmt::format("{}: cannot write the generated volume: {}", file.string(), e.what()));
  }
  std::filesystem::rename(temp, file, ec);
  if (ec) {
    const std::string problem = ec.message();
    std::filesystem::remove(temp, ec);
    throw RuntimeError(
        fmt::format("{}: cannot write the generated volume: {}", file.string(), problem));
  }
}

std::filesystem::path generated_volume_file(const VolumeGenerator& g) {
  const std::filesystem::path file = volume_cache_dir() / generated_volume_name(g);
  if (!std::filesystem::is_regular_file(file)) write_generated_volume(g, file);
  return file;
}

}  // namespace lantern::runtime
