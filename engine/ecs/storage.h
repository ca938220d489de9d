// Storage<T>: a sparse set plus the component values of type T, packed in dense order
// (values()[i] belongs to entities()[i]). See sparse_set.h for why sparse sets.
#pragma once

#include <span>
#include <utility>
#include <vector>

#include "engine/ecs/sparse_set.h"

namespace lantern {

template <class T>
class Storage final : public SparseSet {
 public:
  Storage() : SparseSet(component_id<T>()) {}

  // Adds e's value (e must not have one). Does not fire on_construct: Registry::emplace does,
  // once the value is in place.
  template <class... Args>
  T& emplace(Entity e, Args&&... args) {
    // Value first: if T's constructor throws, the entity has not been added.
    if constexpr (std::is_constructible_v<T, Args...>) {
      values_.emplace_back(std::forward<Args>(args)...);
    } else {
      values_.emplace_back(T{std::forward<Args>(args)...});  // aggregates
    }
    try {
      push_entity(e);
    } catch (...) {
      values_.pop_back();
      throw;
    }
    return values_.back();
  }

  T& at(std::uint32_t i) { return values_[i]; }
  const T& at(std::uint32_t i) const { return values_[i]; }
  std::span<T> values() { return values_; }
  std::span<const T> values() const { return values_; }

 private:
  void swap_pop_value(std::uint32_t i) override {
    if (i + 1 != values_.size()) values_[i] = std::move(values_.back());
    values_.pop_back();
  }

  std::vector<T> values_;
};

}  // namespace lantern
