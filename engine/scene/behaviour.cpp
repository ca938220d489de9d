// Names of behaviour kinds, as spelled in level files.
#include "engine/scene/behaviour.h"

namespace lantern {

const char* behaviour_type_name(const Behaviour& b) {
  constexpr const char* kNames[] = {"rotate", "orbit", "flicker", "follow_path"};
  static_assert(std::variant_size_v<Behaviour> == std::size(kNames));
  return kNames[b.index()];
}

bool behaviour_moves(const Behaviour& b) {
  return !std::holds_alternative<FlickerBehaviour>(b);
}

}  // namespace lantern
