// Entities are generational handles: slot index + generation. Destroying an entity bumps its
// slot's generation, so every copy of the old handle becomes stale and is detected.
#pragma once

#include <string>

#include <fmt/format.h>

#include "engine/core/handle.h"

namespace lantern {

using Entity = Handle<struct EntityTag>;

// "entity 12:3" (index:generation) or "null entity", for error messages.
inline std::string describe(Entity e) {
  if (e.is_null()) return "null entity";
  return fmt::format("entity {}:{}", e.index(), e.generation());
}

}  // namespace lantern
