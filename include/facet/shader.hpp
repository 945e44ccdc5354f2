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
#include "facet/detail/float_fields.hpp"
#include "facet/simd.hpp"

namespace facet {

// Varyings are interpolated as a flat array of floats, so a varyings struct is an aggregate holding only floats
// and glm float vectors (vec2, vec3, vec4), directly or in nested structs and arrays of them: an int, a double, a
// dvec or ivec, a bool or a pointer would be blended as float bits. That keeps interpolation generic, branch-free
// and ready for SIMD. The field check is detail::holds_only_float_fields (facet/detail/float_fields.hpp).
template <class V>
concept Interpolatable = std::is_aggregate_v<V> && std::is_trivially_copyable_v<V> && std::is_standard_layout_v<V> &&
                         sizeof(V) % sizeof(float) == 0 && alignof(V) <= alignof(float) * 4 &&
                         detail::holds_only_float_fields<V>();

template <Interpolatable V>
inline constexpr std::size_t float_count_v = sizeof(V) / sizeof(float);

template <Interpolatable V>
using FloatArray = std::array<float, float_count_v<V>>;

// The message of the Varyings rule, wherever it is checked: VertexOut and Fragment check it themselves, rather than
// by a constraint, so that a shader with a bad Varyings fails at its own definition with the rule's message.
#define FACET_VARYINGS_RULE_                                                                                 \
  "facet shader rule: Varyings holds only float, glm::vec2, glm::vec3 and glm::vec4 members (int, double, " \
  "glm::dvec*, glm::ivec*, bool and pointers are not interpolatable)"

// What vertex() returns: the position in clip space and the values to interpolate across the triangle.
template <class V>
struct VertexOut {
  static_assert(Interpolatable<V>, FACET_VARYINGS_RULE_);
  glm::vec4 clip;
  V varyings;
};

// What fragment() receives for one pixel.
template <class V>
struct Fragment {
  static_assert(Interpolatable<V>, FACET_VARYINGS_RULE_);
  V varyings;          // perspective-correct at the pixel centre
  V ddx{}, ddy{};      // coarse derivatives over the 2x2 quad; zero unless the shader sets needs_derivatives
  glm::vec3 screen{};  // pixel centre in screen space (x right, y down, +0.5 centres) and window depth z in [0, 1]
  std::uint32_t primitive = 0;  // index of the triangle (or line) in the draw's index order
  bool front_facing = true;
};

// The lane types of the optional lane hooks, declared here so that ShaderTraits can check those hooks' shapes. A
// shader with such a hook includes facet/fragment_lanes.hpp or facet/vertex_lanes.hpp, which define them. L is the
// lane layout (simd.hpp): a hook that is a template on it runs each CPU level's layout.
template <Interpolatable V, class L = simd::Whole>
struct FragmentLanes;
template <Interpolatable V, class L = simd::Whole>
struct VertexOutLanes;
template <class Vertex, class L = simd::Whole>
struct VertexLanes;

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
// Optional hooks, a closed list (ShaderTraits<S> is the pipeline's one reader of them and of may_discard):
//   static constexpr bool needs_derivatives = true;      fills Fragment::ddx/ddy (texture level of detail)
//   simd::ColorT<L> fragment_lanes(const FragmentLanes<Varyings, L>&) const;  16 pixels a call, when !may_discard
//   static constexpr bool lanes_read_primitive = false;  fragment_lanes reads neither primitive nor front_facing
//   void prefetch_lanes(const FragmentLanes<Varyings, L>&) const;           with fragment_lanes
//   VertexOutLanes<Varyings, L> vertex_lanes(const VertexLanes<Vertex, L>&) const;   16 vertices a call
// each best a template on the lane layout L (template <class L>), or taking the whole layout's types only.
// (fragment_lanes.hpp and vertex_lanes.hpp say what each does.)

namespace detail {

// A type that declares Vertex and Varyings claims to be a shader: every rule of ShaderTraits then applies to it, as
// a compile error naming the rule rather than a quiet "not a Shader".
template <class S>
concept DeclaresShader = std::is_class_v<S> && requires {
  typename S::Vertex;
  typename S::Varyings;
};

// declares_NAME<S>: whether S has a member called NAME, of any kind, own or inherited, overloaded or a template. In
// a class derived from S and from a struct with such a member, the name is then ambiguous. A final S cannot be
// derived from, so for it only a member whose address can be taken is seen.
#define FACET_MEMBER_PROBE_(name, ...)                                                     \
  struct Named_##name {                                                                    \
    int name;                                                                              \
  };                                                                                       \
  template <class S>                                                                       \
  struct Probe_##name : S, Named_##name {};                                                \
  template <class S>                                                                       \
  concept declares_##name = (!std::is_final_v<S> && !requires { &Probe_##name<S>::name; }) || \
                            (std::is_final_v<S> && requires { &S::name; });

// Names close to a hook's: a shader declaring one almost surely meant the hook, which would otherwise be absent
// without a word (a misspelled needs_derivatives leaves ddx/ddy zero; a misspelled fragment_lanes, the slow path).
#define FACET_NEAR_NAMES_(X)                                                                                   \
  X(needs_derivative, needs_derivatives) X(need_derivatives, needs_derivatives)                                \
  X(need_derivative, needs_derivatives) X(needs_derivates, needs_derivatives)                                  \
  X(uses_derivatives, needs_derivatives) X(requires_derivatives, needs_derivatives)                            \
  X(may_discards, may_discard) X(can_discard, may_discard) X(might_discard, may_discard)                       \
  X(fragment_lane, fragment_lanes) X(fragments_lanes, fragment_lanes) X(fragments_lane, fragment_lanes)        \
  X(frag_lanes, fragment_lanes) X(lanes_fragment, fragment_lanes)                                              \
  X(lane_read_primitive, lanes_read_primitive) X(lanes_reads_primitive, lanes_read_primitive)                  \
  X(lanes_read_primitives, lanes_read_primitive) X(lane_reads_primitive, lanes_read_primitive)                 \
  X(prefetch_lane, prefetch_lanes) X(prefetches_lanes, prefetch_lanes)                                         \
  X(vertex_lane, vertex_lanes) X(vertices_lanes, vertex_lanes) X(vertexes_lanes, vertex_lanes)
FACET_NEAR_NAMES_(FACET_MEMBER_PROBE_)
FACET_MEMBER_PROBE_(needs_derivatives)
FACET_MEMBER_PROBE_(lanes_read_primitive)
FACET_MEMBER_PROBE_(fragment_lanes)
FACET_MEMBER_PROBE_(prefetch_lanes)
FACET_MEMBER_PROBE_(vertex_lanes)
#undef FACET_MEMBER_PROBE_

// A flag is a static constexpr bool: not an int, not a non-static member (which would be per object, not per type).
#define FACET_BOOL_FLAG_(name)                                               \
  template <class S>                                                         \
  concept bool_flag_##name = requires {                                      \
    requires std::same_as<decltype(S::name), const bool>;                    \
    typename std::bool_constant<S::name>;                                    \
  };
FACET_BOOL_FLAG_(may_discard)
FACET_BOOL_FLAG_(needs_derivatives)
FACET_BOOL_FLAG_(lanes_read_primitive)
#undef FACET_BOOL_FLAG_

// The hooks' shapes, called as the pipeline calls them: through a const reference, so that a shader is shared by
// every thread of a draw. Each non-const variant only tells which rule to name.
template <class S, class Self>
concept vertex_on = requires(Self& shader, const typename S::Vertex& vertex) {
  { shader.vertex(vertex) } -> std::same_as<VertexOut<typename S::Varyings>>;
};
template <class S, class Self, class Result>
concept fragment_on = requires(Self& shader, const Fragment<typename S::Varyings>& fragment) {
  { shader.fragment(fragment) } -> std::same_as<Result>;
};
template <class S, class Self, class L = simd::Whole>
concept fragment_lanes_on = requires(Self& shader, const FragmentLanes<typename S::Varyings, L>& fragment) {
  { shader.fragment_lanes(fragment) } -> std::same_as<simd::ColorT<L>>;
};
template <class S, class Self, class L = simd::Whole>
concept prefetch_lanes_on = requires(Self& shader, const FragmentLanes<typename S::Varyings, L>& fragment) {
  { shader.prefetch_lanes(fragment) } -> std::same_as<void>;
};
template <class S, class Self, class L = simd::Whole>
concept vertex_lanes_on = requires(Self& shader, const VertexLanes<typename S::Vertex, L>& vertices) {
  { shader.vertex_lanes(vertices) } -> std::same_as<VertexOutLanes<typename S::Varyings, L>>;
};
// Whether a hook takes every lane layout: a template on it.
template <class S>
concept fragment_lanes_per_level =
    fragment_lanes_on<S, const S, simd::Halves> && fragment_lanes_on<S, const S, simd::Quarters>;
template <class S>
concept prefetch_lanes_per_level =
    prefetch_lanes_on<S, const S, simd::Halves> && prefetch_lanes_on<S, const S, simd::Quarters>;
template <class S>
concept vertex_lanes_per_level =
    vertex_lanes_on<S, const S, simd::Halves> && vertex_lanes_on<S, const S, simd::Quarters>;

}  // namespace detail

// The one reader of a shader's flags and optional hooks, and the checker of their rules: the pipeline asks it, never
// S itself. Every rule is a static_assert whose message begins "facet shader rule:", raised wherever S is checked
// as a Shader (Renderer::draw, FACET_EXTERN_SHADER).
template <class S>
struct ShaderTraits {
  static_assert(detail::DeclaresShader<S>, "facet shader rule: a shader declares the types Vertex and Varyings");

  static constexpr bool may_discard = [] {
    if constexpr (detail::bool_flag_may_discard<S>) return S::may_discard;
    else return false;
  }();
  static constexpr bool needs_derivatives = [] {
    if constexpr (detail::bool_flag_needs_derivatives<S>) return S::needs_derivatives;
    else return false;
  }();
  // False when fragment_lanes reads neither primitive nor front_facing: the pipeline then leaves them unset.
  static constexpr bool lanes_read_primitive = [] {
    if constexpr (detail::bool_flag_lanes_read_primitive<S>) return S::lanes_read_primitive;
    else return true;
  }();
  using FragmentResult = std::conditional_t<may_discard, std::optional<glm::vec4>, glm::vec4>;

 private:
  static constexpr bool kVaryings = Interpolatable<typename S::Varyings>;
  static constexpr bool kVertex = !kVaryings || detail::vertex_on<S, const S>;
  static constexpr bool kFragment = !kVaryings || detail::fragment_on<S, const S, FragmentResult>;
  static constexpr bool kLanes = kVaryings && detail::declares_fragment_lanes<S>;
  static constexpr bool kLanesShape = !kLanes || detail::fragment_lanes_on<S, const S>;
  static constexpr bool kPrefetch = kVaryings && detail::declares_prefetch_lanes<S>;
  static constexpr bool kLanesPerLevel = kLanes && detail::fragment_lanes_per_level<S>;
  static constexpr bool kPrefetchShape =
      !kPrefetch || (detail::prefetch_lanes_on<S, const S> && (!kLanesPerLevel || detail::prefetch_lanes_per_level<S>));
  static constexpr bool kVertexLanes = kVaryings && detail::declares_vertex_lanes<S>;
  static constexpr bool kVertexLanesShape = !kVertexLanes || detail::vertex_lanes_on<S, const S>;

 public:
  static_assert(detail::bool_flag_may_discard<S>,
                "facet shader rule: a shader declares static constexpr bool may_discard");
  static_assert(!detail::declares_needs_derivatives<S> || detail::bool_flag_needs_derivatives<S>,
                "facet shader rule: needs_derivatives is a static constexpr bool");
  static_assert(!detail::declares_lanes_read_primitive<S> || detail::bool_flag_lanes_read_primitive<S>,
                "facet shader rule: lanes_read_primitive is a static constexpr bool");
  static_assert(kVaryings, FACET_VARYINGS_RULE_);
  static_assert(kVertex || !detail::vertex_on<S, S>, "facet shader rule: vertex() is a const member function");
  static_assert(kVertex || detail::vertex_on<S, S>,
                "facet shader rule: vertex() is VertexOut<Varyings> vertex(const Vertex&) const");
  static_assert(kFragment || !detail::fragment_on<S, S, FragmentResult>,
                "facet shader rule: fragment() is a const member function");
  static_assert(kFragment || detail::fragment_on<S, S, FragmentResult>,
                "facet shader rule: fragment() is glm::vec4 fragment(const Fragment<Varyings>&) const, returning "
                "std::optional<glm::vec4> instead when may_discard");
  static_assert(kLanesShape || !detail::fragment_lanes_on<S, S>,
                "facet shader rule: fragment_lanes() is a const member function");
  static_assert(kLanesShape || detail::fragment_lanes_on<S, S>,
                "facet shader rule: fragment_lanes() is template <class L> simd::ColorT<L> fragment_lanes(const "
                "FragmentLanes<Varyings, L>&) const, or simd::Color fragment_lanes(const FragmentLanes<Varyings>&) "
                "const");
  static_assert(!kLanes || !may_discard,
                "facet shader rule: fragment_lanes() needs may_discard = false (lane shading cannot discard)");
  static_assert(!detail::declares_lanes_read_primitive<S> || kLanes,
                "facet shader rule: lanes_read_primitive is declared only with fragment_lanes(), which it describes");
  static_assert(kPrefetchShape, "facet shader rule: prefetch_lanes() is void prefetch_lanes(const "
                                "FragmentLanes<Varyings, L>&) const, for the layouts fragment_lanes() takes");
  static_assert(!kPrefetch || kLanes, "facet shader rule: prefetch_lanes() is declared only with fragment_lanes()");
  static_assert(kVertexLanesShape || !detail::vertex_lanes_on<S, S>,
                "facet shader rule: vertex_lanes() is a const member function");
  static_assert(kVertexLanesShape || detail::vertex_lanes_on<S, S>,
                "facet shader rule: vertex_lanes() is template <class L> VertexOutLanes<Varyings, L> "
                "vertex_lanes(const VertexLanes<Vertex, L>&) const, or the same with the whole layout only");
#define FACET_NOT_NEAR_NAME_(wrong, right)     \
  static_assert(!detail::declares_##wrong<S>, \
                "facet shader rule: " #wrong " is not a shader hook; did you mean " #right "?");
  FACET_NEAR_NAMES_(FACET_NOT_NEAR_NAME_)
#undef FACET_NOT_NEAR_NAME_

  // Whether the pipeline shades 16 fragments per call with fragment_lanes, prefetches with prefetch_lanes, and
  // shades 16 vertices per call with vertex_lanes.
  static constexpr bool fragment_lanes = kLanes && kLanesShape && !may_discard;
  static constexpr bool prefetch_lanes = fragment_lanes && kPrefetch && kPrefetchShape;
  static constexpr bool vertex_lanes = kVertexLanes && kVertexLanesShape;
  // Whether fragment_lanes (and prefetch_lanes) and vertex_lanes are templates on the lane layout, compiled into
  // each CPU level with its own layout (detail/dispatch.hpp), rather than run with the whole layout everywhere.
  static constexpr bool fragment_lanes_per_level = fragment_lanes && kLanesPerLevel;
  static constexpr bool vertex_lanes_per_level = vertex_lanes && detail::vertex_lanes_per_level<S>;
  // Every rule holds (when one does not, its static_assert has already stopped the build).
  static constexpr bool valid = detail::bool_flag_may_discard<S> && kVaryings && kVertex && kFragment && kLanesShape;
};
#undef FACET_NEAR_NAMES_
#undef FACET_VARYINGS_RULE_

template <class S>
concept Shader = detail::DeclaresShader<S> && ShaderTraits<S>::valid;

template <class S>
using FragmentResult = typename ShaderTraits<S>::FragmentResult;

template <Interpolatable V>
inline FloatArray<V> to_floats(const V& v) {
  return detail::bit_cast<FloatArray<V>>(v);
}
template <Interpolatable V>
inline V from_floats(const FloatArray<V>& f) {
  return detail::bit_cast<V>(f);
}

}  // namespace facet
