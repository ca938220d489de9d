// JSON levels: the "volumes" section (docs/levels.md; units: CLI.md "Volume units"). Only the
// entry is read here; the grid file is loaded (and checked) by runtime/volume/.
#include <fmt/format.h>

#include <cmath>

#include "engine/core/error.h"
#include "engine/level/json_level_reader.h"

namespace lantern {
namespace {

// Beyond these a coefficient is a typo, not a medium: 1e6 1/m is a mean free path of a micron.
constexpr float kMaxCoefficient = 1.0e6f;
constexpr float kMaxDensityScale = 1.0e6f;

void check_coefficients(JsonObject& o, std::string_view key, const glm::vec3& c) {
  if (glm::any(glm::lessThan(c, glm::vec3(0.0f))))
    o.fail(key,
           fmt::format("negative coefficient [{}, {}, {}] (must be >= 0, 1/m per unit density)",
                       c.x, c.y, c.z));
  if (glm::any(glm::greaterThan(c, glm::vec3(kMaxCoefficient))))
    o.fail(key, fmt::format("coefficient [{}, {}, {}] is absurd (limit {} 1/m per unit density)",
                            c.x, c.y, c.z, kMaxCoefficient));
}

VolumeGenerator read_volume_generator(JsonObject& g) {
  VolumeGenerator out;
  const std::string type = g.string("type");
  const std::optional<VolumeGeneratorType> t = volume_generator_from_name(type);
  if (!t)
    g.fail("type",
           fmt::format("unknown volume generator '{}' ({})", type, volume_generator_names()));
  out.type = *t;
  out.seed = static_cast<std::uint64_t>(g.integer("seed", 1, 0, 0x7FFFFFFFFFFFFFFFll));
  out.size = g.vec3("size", out.size);
  out.voxel_size = g.number("voxel_size", out.voxel_size);
  if (glm::any(glm::lessThanEqual(out.size, glm::vec3(0.0f))) ||
      glm::any(glm::greaterThan(out.size, glm::vec3(10000.0f))))
    g.fail("size", "each extent must be in (0, 10000] metres");
  if (!(out.voxel_size >= 1e-4f && out.voxel_size <= 100.0f))
    g.fail("voxel_size", "must be in [0.0001, 100] metres");
  const glm::dvec3 counts(out.voxel_counts());
  const double voxels = counts.x * counts.y * counts.z;
  if (voxels > double(kMaxGeneratedVolumeVoxels))
    g.fail("voxel_size",
           fmt::format("{:.0f} x {:.0f} x {:.0f} = {:.0f} voxels exceeds the limit "
                       "of {} voxels for a generated grid (raise voxel_size)",
                       counts.x, counts.y, counts.z, voxels, kMaxGeneratedVolumeVoxels));
  g.finish();
  return out;
}

}  // namespace

void JsonLevelReader::read_volume(JsonObject& o) {
  Volume v;
  v.where = fmt::format("{}: {}", file_.string(), o.pointer());
  if (o.has("file") == o.has("generate"))
    o.fail("give exactly one of 'file' (a .vdb) and 'generate' (a volume generator)");
  if (o.has("file")) {
    v.file = existing_file(o, "file");
    v.name = o.string("name", v.file.stem().string());
  } else {
    JsonObject g = o.object("generate");
    v.generator = read_volume_generator(g);
    v.name = o.string("name", volume_generator_name(v.generator->type));
  }
  v.grid = o.string("grid", v.grid);
  if (v.grid.empty()) o.fail("grid", "the grid name is empty");
  v.transform = read_transform(o);
  v.density_scale = o.number("density_scale", v.density_scale);
  if (!(v.density_scale >= 0.0f))
    o.fail("density_scale", fmt::format("negative density_scale {}", v.density_scale));
  if (v.density_scale > kMaxDensityScale)
    o.fail("density_scale",
           fmt::format("density_scale {} is absurd (limit {})", v.density_scale, kMaxDensityScale));
  v.scattering = o.vec3("scattering", v.scattering);
  check_coefficients(o, "scattering", v.scattering);
  v.absorption = o.vec3("absorption", v.absorption);
  check_coefficients(o, "absorption", v.absorption);
  v.anisotropy = o.number("anisotropy", v.anisotropy);
  if (!(v.anisotropy > -1.0f && v.anisotropy < 1.0f))
    o.fail("anisotropy", fmt::format("Henyey-Greenstein g = {} is outside (-1, 1)", v.anisotropy));
  v.behaviour = behaviour_ref(o);
  if (v.behaviour && std::holds_alternative<FlickerBehaviour>(*v.behaviour))
    o.fail("behaviour",
           "flicker scales emission, and volumes do not emit (use rotate, orbit or "
           "follow_path)");
  o.finish();
  level().volumes.push_back(std::move(v));
}

}  // namespace lantern
