// simd_shuffles.hpp - moving values between lanes: within a 2x2 quad, across a pair of lane values, by a pattern.
#pragma once

#include <utility>

#include "facet/simd.hpp"

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"

namespace facet::simd {

// Lane k of the result is lane pattern[k] of v, or of the lanes of a followed by those of b, for the whole layout
// (the one a pattern is a single vector in). GCC spells this __builtin_shuffle; Clang has only
// __builtin_shufflevector with literal indices, so its build uses a loop, which it folds into one shuffle for the
// constant patterns facet passes.
#if defined(__clang__)
template <class V>
FACET_LANES_INLINE V shuffle(const V& v, const Int& pattern) {
  typename V::Part r;
  for (int k = 0; k < kLanes; ++k) r[k] = v.part[0][pattern.part[0][k] & (kLanes - 1)];
  return r;
}
#else
template <class V>
FACET_LANES_INLINE V shuffle(const V& v, const Int& pattern) {
  return __builtin_shuffle(v.part[0], pattern.part[0]);
}
#endif

// Shuffles one part (or a pair of them) by literal lane numbers: index(k) for lane k of the result.
template <class Index, class Part, int... k>
FACET_LANES_INLINE Part shuffle_part(const Part& a, const Part& b, std::integer_sequence<int, k...>) {
  return __builtin_shufflevector(a, b, Index{}(k)...);
}

// Each lane takes the value of the pixel (kDx, kDy) of its 2x2 quad: coarse derivatives are differences between a
// quad's pixels. With the whole layout that is one shuffle; with halves or quarters each row's parts are shuffled
// within themselves, the quads' rows being whole parts.
template <int kDx, int kDy, class Scalar, class L>
FACET_LANES_INLINE Lanes<Scalar, L> quad_pixel(const Lanes<Scalar, L>& v) {
  using V = Lanes<Scalar, L>;
  constexpr auto lanes = std::make_integer_sequence<int, L::width>{};
  if constexpr (L::parts == 1) {
    const auto index = [](int k) consteval { return (k & ~9) | kDx | (kDy << 3); };
    return V(shuffle_part<decltype(index)>(v.part[0], v.part[0], lanes));
  } else {
    constexpr int kPerRow = L::parts / 2;
    const auto index = [](int k) consteval { return (k & ~1) | kDx; };
    return V::by_part([&](int i) __attribute__((always_inline)) {
      const typename V::Part& row = v.part[kDy * kPerRow + i % kPerRow];
      return shuffle_part<decltype(index)>(row, row, lanes);
    });
  }
}
template <class V>
FACET_LANES_INLINE V quad_top_left(const V& v) {
  return quad_pixel<0, 0>(v);
}
template <class V>
FACET_LANES_INLINE V quad_top_right(const V& v) {
  return quad_pixel<1, 0>(v);
}
template <class V>
FACET_LANES_INLINE V quad_bottom_left(const V& v) {
  return quad_pixel<0, 1>(v);
}

// The even (kOdd 0) or odd (kOdd 1) lanes of the 32 lanes of a followed by those of b: lane k of the result is
// lane 2k + kOdd of the pair. Each part of the result comes from two consecutive parts of the pair.
template <int kOdd, class Scalar, class L>
FACET_LANES_INLINE Lanes<Scalar, L> deinterleave(const Lanes<Scalar, L>& a, const Lanes<Scalar, L>& b) {
  using V = Lanes<Scalar, L>;
  const auto index = [](int k) consteval { return 2 * k + kOdd; };
  return V::by_part([&](int i) __attribute__((always_inline)) {
    const auto source = [&](int q) __attribute__((always_inline)) -> const typename V::Part& {
      return q < L::parts ? a.part[q] : b.part[q - L::parts];
    };
    return shuffle_part<decltype(index)>(source(2 * i), source(2 * i + 1), std::make_integer_sequence<int, L::width>{});
  });
}

}  // namespace facet::simd

#pragma GCC diagnostic pop
