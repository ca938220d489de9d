// Singleton resources: at most one value per type, owned by the registry (`registry.ctx()`).
// For world-wide state that is not per entity: frame settings, the active camera entity, an RNG.
// Create resources before the scheduler runs; systems then only get() them (get() is safe from
// several threads, emplace()/erase() are not).
#pragma once

#include <memory>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "engine/core/error.h"
#include "engine/ecs/type_id.h"

namespace lantern {

class Resources {
 public:
  // Creates (or replaces) the T resource.
  template <class T, class... Args>
  T& emplace(Args&&... args) {
    const TypeId id = component_id<T>();
    if (id >= slots_.size()) slots_.resize(static_cast<std::size_t>(id) + 1);
    T* value = nullptr;
    if constexpr (std::is_constructible_v<T, Args...>) {
      value = new T(std::forward<Args>(args)...);
    } else {
      value = new T{std::forward<Args>(args)...};
    }
    slots_[id] = std::shared_ptr<void>(value);  // remembers to delete it as a T
    return *value;
  }

  template <class T>
  T* find() {
    const TypeId id = component_id<T>();
    return id < slots_.size() ? static_cast<T*>(slots_[id].get()) : nullptr;
  }
  template <class T>
  const T* find() const {
    return const_cast<Resources*>(this)->find<T>();
  }

  // Always-on check: a missing resource is an error naming the type.
  template <class T>
  T& get() {
    if (T* value = find<T>()) return *value;
    throw RuntimeError(fmt::format("resource {} was never created (call ctx().emplace<{}>() first)",
                                   type_name(component_id<T>()), type_name(component_id<T>())));
  }
  template <class T>
  const T& get() const {
    return const_cast<Resources*>(this)->get<T>();
  }

  template <class T>
  bool contains() const {
    return find<T>() != nullptr;
  }

  template <class T>
  bool erase() {
    const TypeId id = component_id<T>();
    if (id >= slots_.size() || !slots_[id]) return false;
    slots_[id].reset();
    return true;
  }

 private:
  // Indexed by component_id<T>(); shared_ptr<void> for its type-erased deleter, never shared.
  std::vector<std::shared_ptr<void>> slots_;
};

}  // namespace lantern
