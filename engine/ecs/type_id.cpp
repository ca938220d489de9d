// The process-wide table behind component_id<T>() (see type_id.h).
#include "engine/ecs/type_id.h"

#include <deque>
#include <mutex>
#include <string>

namespace lantern {
namespace {

struct TypeTable {
  std::mutex mutex;
  std::deque<std::string> names;  // deque: references stay valid as it grows
};

TypeTable& table() {
  static TypeTable t;
  return t;
}

}  // namespace

TypeId detail::register_type(std::string_view name) {
  TypeTable& t = table();
  std::lock_guard lock(t.mutex);
  t.names.emplace_back(name);
  return static_cast<TypeId>(t.names.size() - 1);
}

std::string_view type_name(TypeId id) {
  TypeTable& t = table();
  std::lock_guard lock(t.mutex);
  if (id >= t.names.size()) return "<unknown type>";
  return t.names[id];
}

}  // namespace lantern
