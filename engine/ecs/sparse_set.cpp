// Membership bookkeeping of a sparse set (see sparse_set.h).
#include "engine/ecs/sparse_set.h"

#include "engine/core/error.h"

namespace lantern {

std::uint32_t SparseSet::push_entity(Entity e) {
  LANTERN_ASSERT(!contains(e));
  const std::uint32_t slot = e.index();
  if (slot >= sparse_.size()) sparse_.resize(static_cast<std::size_t>(slot) + 1, kAbsent);
  const auto i = static_cast<std::uint32_t>(dense_.size());
  dense_.push_back(e);
  sparse_[slot] = i;
  return i;
}

bool SparseSet::remove(Registry& registry, Entity e) {
  if (!contains(e)) return false;
  on_destroy_.fire(registry, e);
  // A listener may itself have removed the component.
  const std::uint32_t i = index_of(e);
  if (i == kAbsent) return true;
  const Entity last = dense_.back();
  dense_[i] = last;
  sparse_[last.index()] = i;
  sparse_[e.index()] = kAbsent;
  dense_.pop_back();
  swap_pop_value(i);
  return true;
}

}  // namespace lantern
