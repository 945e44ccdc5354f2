// float_fields.hpp - whether an aggregate holds only floats and glm float vectors, checked without reflection.
#pragma once

#include <concepts>
#include <cstddef>
#include <utility>

#include <glm/glm.hpp>

namespace facet::detail {

// The field types a varyings struct may hold: each is a run of floats, so the struct is a flat array of floats.
template <class T>
concept FloatField = std::same_as<T, float> || std::same_as<T, glm::vec2> || std::same_as<T, glm::vec3> ||
                     std::same_as<T, glm::vec4>;

// Converts to a FloatField type and to nothing else (there is no float -> int path: the conversion is a template
// deduced from the field's own type). So V{FloatLike{} x N} is well-formed exactly when V's first N fields are
// FloatField types; nested aggregates and arrays (of floats) are entered by brace elision and count per field.
// Declared only: it appears in unevaluated requires-expressions.
struct FloatLike {
  template <FloatField T>
  operator T() const;
};
// Converts to any type: placed after the longest run of FloatLike, it initializes whatever field comes next, so
// V{FloatLike{} x N, AnyField{}} is ill-formed only when V has no field left after the first N.
struct AnyField {
  template <class T>
  operator T() const;
};
template <std::size_t>
using FloatLikeAt = FloatLike;

template <class V, std::size_t... I>
consteval bool fields_from_float_like(std::index_sequence<I...>) {
  return requires { V{FloatLikeAt<I>{}...}; };
}
template <class V, std::size_t... I>
consteval bool field_after_float_like(std::index_sequence<I...>) {
  return requires { V{FloatLikeAt<I>{}..., AnyField{}}; };
}

// The length of V's leading run of FloatField fields. A FloatField is at least one float wide, so the run is at
// most sizeof(V) / sizeof(float) long.
template <class V, std::size_t... N>
consteval std::size_t float_field_run(std::index_sequence<N...>) {
  std::size_t run = 0;
  ((fields_from_float_like<V>(std::make_index_sequence<N + 1>{}) ? void(run = N + 1) : void()), ...);
  return run;
}

// True when every field of the aggregate V is a FloatField: the leading run of them is followed by no field at all.
template <class V>
consteval bool holds_only_float_fields() {
  constexpr std::size_t run = float_field_run<V>(std::make_index_sequence<sizeof(V) / sizeof(float)>{});
  return !field_after_float_like<V>(std::make_index_sequence<run>{});
}

}  // namespace facet::detail
