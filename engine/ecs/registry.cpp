// Entity lifetime and error reporting of the registry (see registry.h).
#include "engine/ecs/registry.h"

namespace lantern {

Entity Registry::create() {
  std::uint32_t slot = 0;
  if (!free_.empty()) {
    slot = free_.back();
    free_.pop_back();
  } else {
    if (generations_.size() > Entity::kMaxIndex) {
      throw RuntimeError(fmt::format("registry: too many entities (limit {})", Entity::kMaxIndex + 1));
    }
    slot = static_cast<std::uint32_t>(generations_.size());
    generations_.push_back(0);
  }
  ++alive_;
  return Entity(slot, generations_[slot]);
}

void Registry::destroy(Entity e) {
  if (!valid(e)) {
    throw RuntimeError(fmt::format("registry: destroy({}): {}", describe(e),
                                   e.is_null() ? "null handle" : "stale handle (already destroyed)"));
  }
  for (const auto& pool : pools_) {
    if (pool) pool->remove(*this, e);
  }
  // Bump the generation: every copy of `e` is stale from now on. A slot whose generation would
  // wrap is retired (never reused), so old handles can never match a new entity.
  std::uint32_t& generation = generations_[e.index()];
  ++generation;
  if (generation < Entity::kMaxGeneration) free_.push_back(e.index());
  --alive_;
}

void Registry::missing(Entity e, const char* op, TypeId type) const {
  fail(e, op, type, valid(e) ? "entity has no such component" : (e.is_null() ? "null handle" : "stale handle (entity was destroyed)"));
}

void Registry::fail(Entity e, const char* op, TypeId type, const char* why) {
  throw RuntimeError(fmt::format("registry: {}<{}>({}): {}", op, type_name(type), describe(e), why));
}

}  // namespace lantern
