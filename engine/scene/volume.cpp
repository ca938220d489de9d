// Names of volume generators, as spelled in level files: one table for both directions.
#include "engine/scene/volume.h"

#include <iterator>

namespace lantern {
namespace {

struct GeneratorName {
  VolumeGeneratorType type;
  const char* name;
};
constexpr GeneratorName kGeneratorNames[] = {
    {VolumeGeneratorType::Constant, "constant"},
    {VolumeGeneratorType::SmokePlume, "smoke_plume"},
    {VolumeGeneratorType::GroundFog, "ground_fog"},
};

}  // namespace

const char* volume_generator_name(VolumeGeneratorType type) {
  for (const GeneratorName& g : kGeneratorNames)
    if (g.type == type) return g.name;
  return "?";
}

std::optional<VolumeGeneratorType> volume_generator_from_name(std::string_view name) {
  for (const GeneratorName& g : kGeneratorNames)
    if (name == g.name) return g.type;
  return std::nullopt;
}

std::string volume_generator_names() {
  std::string out;
  for (const GeneratorName& g : kGeneratorNames)
    out += (out.empty() ? "" : ", ") + std::string(g.name);
  return out;
}

}  // namespace lantern
