// View<T...>: the entities that have all of T..., visited with their components.
// Iteration walks the smallest of the sets and probes the others (one sparse lookup each).
// It goes back to front, so removing the current entity's components, or adding entities, inside
// the loop is safe; removing other visited entities' components is not.
// `View<const A, B>` gives `const A&`: declare reads as const to make intent visible.
#pragma once

#include <array>
#include <cstdint>
#include <tuple>
#include <type_traits>
#include <utility>

#include "engine/ecs/storage.h"

namespace lantern {

template <class... T>
class View {
  static_assert(sizeof...(T) > 0, "a view needs at least one component type");

 public:
  explicit View(Storage<std::remove_const_t<T>>&... pools) : pools_(&pools...) {
    lead_ = nullptr;
    ((lead_ = (lead_ == nullptr || pools.size() < lead_->size()) ? &pools : lead_), ...);
  }

  // Upper bound on the number of entities visited (the size of the smallest set).
  std::size_t size_hint() const { return lead_->size(); }

  bool contains(Entity e) const {
    return std::apply([e](auto*... p) { return (p->contains(e) && ...); }, pools_);
  }

  // Calls fn(entity, T&...) or fn(T&...) for every entity that has all of T.
  template <class Fn>
  void each(Fn&& fn) const {
    each_impl(fn, std::index_sequence_for<T...>{});
  }

 private:
  template <class Fn, std::size_t... K>
  void each_impl(Fn& fn, std::index_sequence<K...>) const {
    const std::span<const Entity> entities = lead_->entities();
    for (std::size_t n = entities.size(); n-- > 0;) {
      const Entity e = entities[n];
      std::array<std::uint32_t, sizeof...(T)> at{};
      const bool all = (((at[K] = locate(std::get<K>(pools_), e, n)) != SparseSet::kAbsent) && ...);
      if (!all) continue;
      if constexpr (std::is_invocable_v<Fn&, Entity, T&...>) {
        fn(e, static_cast<T&>(std::get<K>(pools_)->at(at[K]))...);
      } else {
        fn(static_cast<T&>(std::get<K>(pools_)->at(at[K]))...);
      }
    }
  }

  // The lead set is walked by position; the others are probed.
  std::uint32_t locate(const SparseSet* pool, Entity e, std::size_t n) const {
    return pool == lead_ ? static_cast<std::uint32_t>(n) : pool->index_of(e);
  }

  std::tuple<Storage<std::remove_const_t<T>>*...> pools_;
  const SparseSet* lead_;
};

}  // namespace lantern
