// named.hpp - a choice and its name (Named<T>), and lookups in a table of them; the tables are in names.hpp.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace facet {

// A choice and its name, as `facet render` spells it (--shading blinn-phong) and the other faces accept it.
template <class T>
struct Named {
  const char* name;
  T value;
};

// The value named `name`; nullopt for anything else.
template <class T>
std::optional<T> parse_name(std::span<const Named<T>> names, std::string_view name) {
  for (const Named<T>& n : names)
    if (name == n.name) return n.value;
  return std::nullopt;
}
// The name of `value` (every value has one).
template <class T>
const char* name_of(std::span<const Named<T>> names, T value) {
  for (const Named<T>& n : names)
    if (n.value == value) return n.name;
  return "";
}
// The names joined by ", ", for messages that say what is accepted.
template <class T>
std::string listed(std::span<const Named<T>> names) {
  std::string out;
  for (const Named<T>& n : names) out += (out.empty() ? "" : ", ") + std::string(n.name);
  return out;
}

}  // namespace facet
