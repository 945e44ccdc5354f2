// fragment_lanes.hpp - the optional 16-lane fragment function: a shader that has one shades a strip at a time.
#pragma once

#include <array>
#include <concepts>
#include <cstddef>
#include <cstdint>

#include "facet/shader.hpp"
#include "facet/simd.hpp"

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"

namespace facet {

// Sixteen fragments: the 8x2 strip of pixels (x0 + k % 8, y0 + k / 8) for lane k, as lane values of layout L
// (simd.hpp; a lane shader's fragment_lanes is best a template on it, see LaneShader). Varyings are stored
// structure-of-arrays, one lane value per float of the Varyings struct; read them by member with get(). Each lane
// holds the triangle that is visible there; lanes where none is (see active) hold another of the strip's
// triangles, as helper lanes, and their results are discarded.
template <Interpolatable V, class L>
struct alignas(simd::kLaneAlign) FragmentLanes {
  using Float = simd::FloatT<L>;
  using Int = simd::IntT<L>;
  using UInt = simd::UIntT<L>;
  using Mask = simd::MaskT<L>;
  using Vec2 = simd::Vec2T<L>;
  using Vec3 = simd::Vec3T<L>;
  using Color = simd::ColorT<L>;
  static constexpr std::size_t kFloats = float_count_v<V>;
  std::array<Float, kFloats> varyings;
  std::array<Float, kFloats> ddx, ddy;  // coarse, per 2x2 quad; filled only when needs_derivatives
  Float screen_x, screen_y, depth;      // as Fragment::screen
  Mask active;                          // the lanes whose colour will be written
  // Per lane, as Fragment's: the lanes of one strip may come from different triangles. Unset for a shader that
  // declares it does not read them (see lanes_read_primitive).
  UInt primitive;
  Mask front_facing;  // -1 where front-facing

  // Position of a member within V, in floats. The probe object is folded away by the optimiser.
  template <class M>
  static std::size_t float_index(M V::*member) {
    const V probe{};
    return static_cast<std::size_t>(reinterpret_cast<const char*>(&(probe.*member)) -
                                    reinterpret_cast<const char*>(&probe)) /
           sizeof(float);
  }

  FACET_LANES_INLINE Float get(float V::*member) const { return varyings[float_index(member)]; }
  FACET_LANES_INLINE Vec2 get(glm::vec2 V::*member) const {
    const std::size_t i = float_index(member);
    return {varyings[i], varyings[i + 1]};
  }
  FACET_LANES_INLINE Vec3 get(glm::vec3 V::*member) const {
    const std::size_t i = float_index(member);
    return {varyings[i], varyings[i + 1], varyings[i + 2]};
  }
  FACET_LANES_INLINE Color get(glm::vec4 V::*member) const {
    const std::size_t i = float_index(member);
    return {varyings[i], varyings[i + 1], varyings[i + 2], varyings[i + 3]};
  }
  // Lane k as a scalar Fragment, for shaders that leave their rare cases to fragment().
  Fragment<V> lane(int k) const {
    Fragment<V> f;
    float* values = reinterpret_cast<float*>(&f.varyings);
    float* dx = reinterpret_cast<float*>(&f.ddx);
    float* dy = reinterpret_cast<float*>(&f.ddy);
    for (std::size_t i = 0; i < kFloats; ++i) {
      values[i] = varyings[i][k];
      dx[i] = ddx[i][k];
      dy[i] = ddy[i][k];
    }
    f.screen = glm::vec3(screen_x[k], screen_y[k], depth[k]);
    f.primitive = primitive[k];
    f.front_facing = front_facing[k] != 0;
    return f;
  }
};

// A shader's fragment() on each of the 16 lanes in turn: what a lane function falls back to for its rare cases (a
// normal-mapped material, say).
template <class S, class V, class L>
FACET_LANES_INLINE simd::ColorT<L> fragment_each_lane(const S& shader, const FragmentLanes<V, L>& f) {
  simd::ColorT<L> out;
  for (int k = 0; k < simd::kLanes; ++k) {
    const glm::vec4 c = shader.fragment(f.lane(k));
    out.r[k] = c.r, out.g[k] = c.g, out.b[k] = c.b, out.a[k] = c.a;
  }
  return out;
}

// A LaneShader is a Shader that also has
//     template <class L>
//     simd::ColorT<L> fragment_lanes(const FragmentLanes<Varyings, L>&) const;
// computing, lane for lane, what fragment() computes. The pipeline then shades 16 fragments per call instead of
// one; fragment() stays the definition (and the path for shaders without a lane version). As a template on the
// lane layout L it is compiled into each CPU level's copy of the pipeline with that level's registers (simd.hpp);
// written with the layout-free names instead,
//     simd::Color fragment_lanes(const FragmentLanes<Varyings>&) const;
// it runs at every level with the whole layout, which below AVX-512 lives in memory (2-3 times slower). Lane shading
// is used only for shaders that cannot discard, so a discarding shader with fragment_lanes does not compile
// (ShaderTraits). Declare it FACET_LANES_INLINE, and its helpers too, for speed: a function left out of line is
// compiled for the baseline ISA only. It still computes the right values, since lane types pass between functions
// through memory in every ISA (simd.hpp).
//
// A LaneShader may also declare
//     static constexpr bool lanes_read_primitive = false;
// when its fragment_lanes reads neither primitive nor front_facing: the pipeline then leaves them unset. Each of a
// strip's triangles would otherwise blend both into their lanes, which on sphere:224 costs 4.5% of a frame's
// instructions (AVX2 copy) for values the benchmark shader never looks at.
template <class S>
concept LaneShader = Shader<S> && ShaderTraits<S>::fragment_lanes;

// A LaneShader may also have
//     template <class L> void prefetch_lanes(const FragmentLanes<Varyings, L>&) const;
// which the pipeline calls with each strip's fragments a few strips before it calls fragment_lanes with them, so
// that the memory the shader will read (texture lines, mostly: see Texture::prefetch_lanes) is on its way by then.
// It must not change anything the shader computes; it only hides memory latency.
template <class S>
concept PrefetchingLaneShader = LaneShader<S> && ShaderTraits<S>::prefetch_lanes;

}  // namespace facet

#pragma GCC diagnostic pop
