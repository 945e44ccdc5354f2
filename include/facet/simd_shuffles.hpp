// simd_shuffles.hpp - moving values between lanes: within a 2x2 quad, across a pair, by a pattern; records transposed.
#pragma once

#include <array>
#include <cstdint>
#include <cstring>
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

// Two vectors of n floats side by side: one vector of 2n.
template <int kFloats, int... k>
FACET_LANES_INLINE native::Vector<float, 2 * kFloats> join(const native::Vector<float, kFloats>& a,
                                                           const native::Vector<float, kFloats>& b,
                                                           std::integer_sequence<int, k...>) {
  return __builtin_shufflevector(a, b, k...);
}

// kCount records of kFloats floats, base + at[first], base + at[first + 1], ..., side by side in one vector: one
// load per record, then joins.
template <int kCount, int kFloats>
FACET_LANES_INLINE native::Vector<float, kCount * kFloats> records_side_by_side(const float* base,
                                                                              const std::int32_t* at, int first) {
  if constexpr (kCount == 1) {
    native::Vector<float, kFloats> record;
    std::memcpy(&record, base + at[first], sizeof record);
    return record;
  } else {
    constexpr int kHalf = kCount / 2;
    return join<kHalf * kFloats>(records_side_by_side<kHalf, kFloats>(base, at, first),
                                 records_side_by_side<kHalf, kFloats>(base, at, first + kHalf),
                                 std::make_integer_sequence<int, kCount * kFloats>{});
  }
}

// Records of kFloats (2 or 4) consecutive floats, one per lane: lane k of result c is base[offset[k] + c]. Each
// lane's record is one load, and the 16 records are transposed by shuffles (two rounds of deinterleave), where
// reading them as floats, lane by lane, costs a load and an insert per float. The same values either way.
template <int kFloats, class L>
FACET_LANES_INLINE std::array<FloatT<L>, kFloats> gather_records(const float* base, const IntT<L>& offset) {
  static_assert(kFloats == 2 || kFloats == 4);
  using Float = FloatT<L>;
  alignas(kLaneAlign) std::int32_t at[kLanes];
  store(at, offset);
  // Block q holds the records of lanes q * (16 / kFloats) onwards, in order: 16 floats, kFloats to a lane.
  constexpr int kBlockLanes = kLanes / kFloats, kPartRecords = L::width / kFloats;
  std::array<Float, kFloats> block;
  for (int q = 0; q < kFloats; ++q)
    block[static_cast<std::size_t>(q)] = Float::by_part([&](int i) __attribute__((always_inline)) {
      return records_side_by_side<kPartRecords, kFloats>(base, at, q * kBlockLanes + i * kPartRecords);
    });
  if constexpr (kFloats == 2) {
    return {deinterleave<0>(block[0], block[1]), deinterleave<1>(block[0], block[1])};
  } else {
    // Even floats (x, z of each record) and odd ones (y, w), then each of those split again.
    const Float even_low = deinterleave<0>(block[0], block[1]), odd_low = deinterleave<1>(block[0], block[1]);
    const Float even_high = deinterleave<0>(block[2], block[3]), odd_high = deinterleave<1>(block[2], block[3]);
    return {deinterleave<0>(even_low, even_high), deinterleave<0>(odd_low, odd_high),
            deinterleave<1>(even_low, even_high), deinterleave<1>(odd_low, odd_high)};
  }
}

}  // namespace facet::simd

#pragma GCC diagnostic pop
