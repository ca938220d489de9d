// A list of listeners called with (registry, entity) when a component is added, changed or
// removed. Listeners run on the thread that made the change, in connection order.
#pragma once

#include <cstdint>
#include <functional>
#include <utility>
#include <vector>

#include "engine/ecs/entity.h"

namespace lantern {

class Registry;

class Signal {
 public:
  using Listener = std::function<void(Registry&, Entity)>;
  using Connection = std::uint32_t;

  Connection connect(Listener listener) {
    listeners_.emplace_back(next_, std::move(listener));
    return next_++;
  }
  void disconnect(Connection c) {
    std::erase_if(listeners_, [c](const auto& l) { return l.first == c; });
  }
  void fire(Registry& registry, Entity e) const {
    for (const auto& l : listeners_) l.second(registry, e);
  }
  bool empty() const { return listeners_.empty(); }

 private:
  std::vector<std::pair<Connection, Listener>> listeners_;
  Connection next_ = 0;
};

}  // namespace lantern
