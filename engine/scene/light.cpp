// Names of light kinds, as spelled in level files and in `lantern info`.
#include "engine/scene/light.h"

namespace lantern {

const char* light_type_name(LightType type) {
  switch (type) {
    case LightType::Point:
      return "point";
    case LightType::Spot:
      return "spot";
    case LightType::Directional:
      return "directional";
  }
  return "?";
}

}  // namespace lantern
