// Component storage is a sparse set per component type. Why sparse sets rather than archetypes:
// - add/remove is O(1) and touches one type's arrays only (no moving a whole row of components
//   between archetype tables), and a component's address changes only when another element of
//   the same type is removed (swap-and-pop);
// - iteration over one type is a dense, packed array walk;
// - it is simple: one array pair per type, easy to test and to reason about under threads
//   (systems writing different types never touch the same memory).
// Archetypes would make iterating several components together faster (all rows packed side by
// side) at the price of expensive add/remove; our views iterate the smallest set and probe the
// others, which is enough for the entity counts the lighting scenes have.
//
// SparseSet is the type-erased part (which entities are members, signals); Storage<T> adds the
// component values in a vector kept parallel to the dense entity array.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "engine/ecs/entity.h"
#include "engine/ecs/signal.h"
#include "engine/ecs/type_id.h"

namespace lantern {

class SparseSet {
 public:
  static constexpr std::uint32_t kAbsent = 0xFFFFFFFFu;

  explicit SparseSet(TypeId type) : type_(type) {}
  virtual ~SparseSet() = default;
  SparseSet(const SparseSet&) = delete;
  SparseSet& operator=(const SparseSet&) = delete;

  TypeId type() const { return type_; }
  std::size_t size() const { return dense_.size(); }
  bool empty() const { return dense_.empty(); }

  // Position of `e` in the dense array, or kAbsent. The full handle (with generation) must
  // match, so a stale handle is never mistaken for the slot's new occupant.
  std::uint32_t index_of(Entity e) const {
    const std::uint32_t slot = e.index();
    if (slot >= sparse_.size()) return kAbsent;
    const std::uint32_t i = sparse_[slot];
    return (i < dense_.size() && dense_[i] == e) ? i : kAbsent;
  }
  bool contains(Entity e) const { return index_of(e) != kAbsent; }

  // Members in dense order (the order views and each() visit them, back to front).
  std::span<const Entity> entities() const { return dense_; }

  // Removes e's component: fires on_destroy first (the value is still readable), then
  // swap-and-pops. Returns false if e had none.
  bool remove(Registry& registry, Entity e);

  Signal& on_construct() { return on_construct_; }
  Signal& on_update() { return on_update_; }
  Signal& on_destroy() { return on_destroy_; }

 protected:
  // Appends e (which must be absent) and returns its dense index.
  std::uint32_t push_entity(Entity e);
  // Storage<T> moves its last value into `i` and pops, mirroring the entity swap.
  virtual void swap_pop_value(std::uint32_t i) = 0;

 private:
  TypeId type_;
  std::vector<Entity> dense_;
  // Indexed by entity slot; flat rather than paged: 4 bytes per slot ever used is cheap at our
  // entity counts and keeps the lookup one load.
  std::vector<std::uint32_t> sparse_;
  Signal on_construct_, on_update_, on_destroy_;
};

}  // namespace lantern
