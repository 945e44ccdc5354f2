// shader.hpp - the Shader concept: a plain struct with vertex() and fragment(), checked at compile time.
#pragma once

#include <array>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <type_traits>

#include <glm/glm.hpp>

#include "facet/detail/bits.hpp"

namespace facet {

// Varyings are interpolated as a flat array of floats, so a varyings struct may hold only floats and glm float
// vectors (vec2, vec3, vec4). That keeps interpolation generic, branch-free and ready for SIMD.
template <class V>
concept Interpolatable = std::is_trivially_copyable_v<V> && std::is_standard_layout_v<V> && sizeof(V) % sizeof(float) ==
                             0 &&
                         alignof(V) <= alignof(float) * 4;

template <Interpolatable V>
inline constexpr std::size_t float_count_v = sizeof(V) / sizeof(float);

template <Interpolatable V>
using FloatArray = std::array<float, float_count_v<V>>;

// What vertex() returns: the position in clip space and the values to interpolate across the triangle.
template <Interpolatable V>
struct VertexOut {
  glm::vec4 clip;
  V varyings;
};

// What fragment() receives for one pixel.
template <Interpolatable V>
struct Fragment {
  V varyings;          // perspective-correct at the pixel centre
  V ddx{}, ddy{};      // coarse derivatives over the 2x2 quad; zero unless the shader sets needs_derivatives
  glm::vec3 screen{};  // pixel centre in screen space (x right, y down, +0.5 centres) and window depth z in [0, 1]
  std::uint32_t primitive = 0;  // index of the triangle (or line) in the draw's index order
  bool front_facing = true;
};

// A shader is a plain struct: uniforms are its data members, and the pipeline is instantiated on its type, so
// there is no virtual call, std::function or allocation per vertex, triangle or pixel.
//
//   struct MyShader {
//     using Vertex = ...;                          // what one element of the vertex span holds
//     struct Varyings { glm::vec3 normal; };       // floats only
//     static constexpr bool may_discard = false;   // false allows the depth test before shading
//     glm::mat4 clip_from_object;                  // a uniform
//     VertexOut<Varyings> vertex(const Vertex&) const;
//     glm::vec4 fragment(const Fragment<Varyings>&) const;   // std::optional<glm::vec4> when may_discard
//   };
//
// Optional: `static constexpr bool needs_derivatives = true;` fills Fragment::ddx/ddy (texture level of detail).
template <class S>
using FragmentResult = std::conditional_t<S::may_discard, std::optional<glm::vec4>, glm::vec4>;

template <class S>
concept Shader = requires(const S& shader, const typename S::Vertex& vertex,
                          const Fragment<typename S::Varyings>& fragment) {
  typename S::Vertex;
  typename S::Varyings;
  requires Interpolatable<typename S::Varyings>;
  { S::may_discard } -> std::convertible_to<bool>;
  { shader.vertex(vertex) } -> std::same_as<VertexOut<typename S::Varyings>>;
  { shader.fragment(fragment) } -> std::same_as<FragmentResult<S>>;
};

template <class S>
constexpr bool needs_derivatives() {
  if constexpr (requires { S::needs_derivatives; }) return S::needs_derivatives;
  else return false;
}

template <Interpolatable V>
inline FloatArray<V> to_floats(const V& v) {
  return detail::bit_cast<FloatArray<V>>(v);
}
template <Interpolatable V>
inline V from_floats(const FloatArray<V>& f) {
  return detail::bit_cast<V>(f);
}

}  // namespace facet
