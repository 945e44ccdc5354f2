// vertex_lanes.hpp - the optional 16-lane vertex function: a shader that has one shades 16 vertices per call.
#pragma once

#include <array>
#include <concepts>
#include <cstddef>

#include <glm/glm.hpp>

#include "facet/fragment_lanes.hpp"
#include "facet/shader.hpp"
#include "facet/simd.hpp"

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"

namespace facet {

// Sixteen consecutive vertices of a draw: lane k is vertices[k], as lane values of layout L. Read them by member with
// get().
template <class Vertex, class L>
struct VertexLanes {
  const Vertex* vertices;

  FACET_LANES_INLINE simd::FloatT<L> get(float Vertex::*member) const {
    simd::FloatT<L> r;
    for (int k = 0; k < simd::kLanes; ++k) r[k] = vertices[k].*member;
    return r;
  }
  FACET_LANES_INLINE simd::Vec2T<L> get(glm::vec2 Vertex::*member) const {
    simd::Vec2T<L> r;
    for (int k = 0; k < simd::kLanes; ++k) r.x[k] = (vertices[k].*member).x, r.y[k] = (vertices[k].*member).y;
    return r;
  }
  FACET_LANES_INLINE simd::Vec3T<L> get(glm::vec3 Vertex::*member) const {
    simd::Vec3T<L> r;
    for (int k = 0; k < simd::kLanes; ++k) {
      const glm::vec3& v = vertices[k].*member;
      r.x[k] = v.x, r.y[k] = v.y, r.z[k] = v.z;
    }
    return r;
  }
};

// What vertex_lanes returns: sixteen clip positions and sets of varyings, one lane value per coordinate and per
// float of the Varyings struct. Write varyings by member with set().
template <Interpolatable V, class L>
struct alignas(simd::kLaneAlign) VertexOutLanes {
  using Float = simd::FloatT<L>;
  static constexpr std::size_t kFloats = float_count_v<V>;
  Float clip_x, clip_y, clip_z, clip_w;
  std::array<Float, kFloats> varyings;

  FACET_LANES_INLINE void set(float V::*member, const Float& v) { varyings[FragmentLanes<V>::float_index(member)] = v; }
  FACET_LANES_INLINE void set(glm::vec2 V::*member, const simd::Vec2T<L>& v) {
    const std::size_t i = FragmentLanes<V>::float_index(member);
    varyings[i] = v.x, varyings[i + 1] = v.y;
  }
  FACET_LANES_INLINE void set(glm::vec3 V::*member, const simd::Vec3T<L>& v) {
    const std::size_t i = FragmentLanes<V>::float_index(member);
    varyings[i] = v.x, varyings[i + 1] = v.y, varyings[i + 2] = v.z;
  }
};

// A LaneVertexShader is a Shader that also has
//     template <class L>
//     VertexOutLanes<Varyings, L> vertex_lanes(const VertexLanes<Vertex, L>&) const;
// (or the same for the whole layout only, as fragment_lanes),
// computing, lane for lane, what vertex() computes, with the same operations in the same order (then both give
// identical images: facet builds without floating-point contraction). The vertex stage then shades 16 vertices
// per call and the rest of a draw one at a time; vertex() stays the definition. Declare it FACET_LANES_INLINE,
// like fragment_lanes, so that it is compiled inside each CPU level's copy of the vertex stage.
template <class S>
concept LaneVertexShader = Shader<S> && ShaderTraits<S>::vertex_lanes;

}  // namespace facet

#pragma GCC diagnostic pop
