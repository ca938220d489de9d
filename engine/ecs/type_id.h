// Process-stable ids for C++ types: component_id<T>() numbers each component (or resource) type
// densely from 0 on first use, so storages and scheduler access sets are indexed by a small int.
// Ids are stable for the life of the process, not across runs: never persist them.
#pragma once

#include <cstdint>
#include <string_view>
#include <type_traits>

namespace lantern {

using TypeId = std::uint32_t;

namespace detail {

// Allocates the next id and records its readable name (for messages and scheduler dumps).
TypeId register_type(std::string_view name);

template <class T>
constexpr std::string_view pretty_type_name() {
  // GCC/Clang: "... [with T = Foo; ...]" or "... [T = Foo]".
  constexpr std::string_view f = __PRETTY_FUNCTION__;
  constexpr std::size_t start = f.find("T = ") + 4;
  constexpr std::size_t end = f.find_first_of(";]", start);
  return f.substr(start, end - start);
}

template <class T>
TypeId type_id_of() {
  static const TypeId id = register_type(pretty_type_name<T>());
  return id;
}

}  // namespace detail

// The id of T; const/volatile qualifiers are ignored (view<const A> and view<A> share A's id).
template <class T>
TypeId component_id() {
  return detail::type_id_of<std::remove_cv_t<T>>();
}

// The readable name recorded for an id ("Velocity", "lantern::Transform").
std::string_view type_name(TypeId id);

}  // namespace lantern
