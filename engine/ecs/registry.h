// The registry: entities, their components (one Storage<T> per type), signals and resources.
//
// Misuse is an always-on checked error (RuntimeError naming the entity and the type): using a
// stale or null handle, getting a component an entity lacks, adding one it already has. A stale
// handle never reaches another entity's data.
//
// Threads: the scheduler runs systems in parallel. Concurrent access to *different* component
// types is safe once their storages exist (the scheduler creates the declared ones before a
// frame). Creating or destroying entities changes shared state: do it in a system marked
// exclusive(), or outside the scheduler.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "engine/core/error.h"
#include "engine/ecs/entity.h"
#include "engine/ecs/resources.h"
#include "engine/ecs/storage.h"
#include "engine/ecs/view.h"

namespace lantern {

class Registry {
 public:
  Registry() = default;
  Registry(const Registry&) = delete;
  Registry& operator=(const Registry&) = delete;

  // --- entities ---------------------------------------------------------------------------
  Entity create();
  // Removes all of e's components (on_destroy fires for each), then invalidates every handle to e.
  void destroy(Entity e);
  bool valid(Entity e) const {
    return e.index() < generations_.size() && generations_[e.index()] == e.generation();
  }
  std::size_t alive() const { return alive_; }

  // --- components ----------------------------------------------------------------------------
  // Adds T to e and fires on_construct<T>. Error if e is not valid or already has a T.
  template <class T, class... Args>
  T& emplace(Entity e, Args&&... args) {
    check_valid(e, "emplace", component_id<T>());
    Storage<T>& s = storage<T>();
    if (s.contains(e)) fail(e, "emplace", component_id<T>(), "already has one");
    s.emplace(e, std::forward<Args>(args)...);
    s.on_construct().fire(*this, e);
    return get<T>(e);  // re-found: a listener may have added or removed T values meanwhile
  }

  template <class T>
  T& get(Entity e) {
    Storage<T>& s = storage<T>();
    const std::uint32_t i = s.index_of(e);
    if (i == SparseSet::kAbsent) missing(e, "get", component_id<T>());
    return s.at(i);
  }
  // The const overloads never create a storage, so they are safe beside other readers.
  template <class T>
  const T& get(Entity e) const {
    if (const T* value = try_get<T>(e)) return *value;
    missing(e, "get", component_id<T>());
  }

  // nullptr when e (stale or not) has no T.
  template <class T>
  T* try_get(Entity e) {
    Storage<T>* s = find_storage<T>();
    if (s == nullptr) return nullptr;
    const std::uint32_t i = s->index_of(e);
    return i == SparseSet::kAbsent ? nullptr : &s->at(i);
  }
  template <class T>
  const T* try_get(Entity e) const {
    return const_cast<Registry*>(this)->try_get<T>(e);
  }

  template <class T>
  bool has(Entity e) const {
    const Storage<T>* s = find_storage<T>();
    return s != nullptr && s->contains(e);
  }
  template <class... T>
  bool all_of(Entity e) const {
    return (has<T>(e) && ...);
  }

  // Changes e's T in place through fn(T&), then fires on_update<T>. Systems change components
  // this way (or with replace) when others listen for changes.
  template <class T, class Fn>
  T& patch(Entity e, Fn&& fn) {
    T& value = get<T>(e);
    std::forward<Fn>(fn)(value);
    storage<T>().on_update().fire(*this, e);
    return value;
  }
  template <class T>
  T& replace(Entity e, T value) {
    return patch<T>(e, [&value](T& current) { current = std::move(value); });
  }
  template <class T, class... Args>
  T& emplace_or_replace(Entity e, Args&&... args) {
    if (all_of<T>(e)) return replace<T>(e, T{std::forward<Args>(args)...});
    return emplace<T>(e, std::forward<Args>(args)...);
  }

  // Removes e's T (on_destroy<T> fires first). Returns false if it had none.
  template <class T>
  bool remove(Entity e) {
    check_valid(e, "remove", component_id<T>());
    Storage<T>* s = find_storage<T>();
    return s != nullptr && s->remove(*this, e);
  }

  template <class... T>
  View<T...> view() {
    return View<T...>(storage<std::remove_const_t<T>>()...);
  }

  // The storage of T, created on first use.
  template <class T>
  Storage<T>& storage() {
    static_assert(!std::is_const_v<T> && !std::is_reference_v<T>);
    const TypeId id = component_id<T>();
    if (id >= pools_.size()) pools_.resize(static_cast<std::size_t>(id) + 1);
    if (!pools_[id]) pools_[id] = std::make_unique<Storage<T>>();
    return static_cast<Storage<T>&>(*pools_[id]);
  }
  template <class T>
  Storage<T>* find_storage() const {
    const TypeId id = component_id<T>();
    return id < pools_.size() ? static_cast<Storage<T>*>(pools_[id].get()) : nullptr;
  }

  // --- signals (fire after add, after change, before removal) --------------------------------
  template <class T>
  Signal& on_construct() {
    return storage<T>().on_construct();
  }
  template <class T>
  Signal& on_update() {
    return storage<T>().on_update();
  }
  template <class T>
  Signal& on_destroy() {
    return storage<T>().on_destroy();
  }

  // --- singleton resources -----------------------------------------------------------------
  Resources& ctx() { return resources_; }
  const Resources& ctx() const { return resources_; }

 private:
  void check_valid(Entity e, const char* op, TypeId type) const {
    if (!valid(e)) fail(e, op, type, e.is_null() ? "null handle" : "stale handle (entity was destroyed)");
  }
  [[noreturn]] void missing(Entity e, const char* op, TypeId type) const;
  [[noreturn]] static void fail(Entity e, const char* op, TypeId type, const char* why);

  std::vector<std::uint32_t> generations_;  // per slot; equals a handle's generation iff alive
  std::vector<std::uint32_t> free_;         // reusable slots, last freed first
  std::size_t alive_ = 0;
  std::vector<std::unique_ptr<SparseSet>> pools_;  // indexed by component_id
  Resources resources_;
};

}  // namespace lantern
