// simd.hpp - 16-lane float and int types for shading a strip of fragments at once, and the lane maths shaders use.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <type_traits>
#include <utility>

#include <glm/vec3.hpp>
#if defined(__wasm_simd128__)
#include <wasm_simd128.h>
#endif

// The lane types wrap GCC/Clang vector extensions rather than intrinsics: the compiler lowers each operation for the
// instruction set of the function it ends up in (each CPU level's copy, detail/dispatch.hpp). Sixteen lanes are
// held as one, two or four native vectors, a layout per CPU level (Layout below): one 512-bit register with
// AVX-512, two 256-bit ones with AVX2, four 128-bit ones with SSE, NEON and WebAssembly SIMD. A layout wider than
// the level's registers would have no machine mode there, and GCC 12 keeps such values in memory between
// operations (docs/PERFORMANCE.md, "Every CPU level"). Lane code is a template on the layout, so one source
// compiles to each level's registers; the names without a layout (Float, Vec3, ...) are the whole 16-lane layout.
// GCC 12 lowers a few idioms element by element when they are inlined from the baseline into a level's copy;
// docs/ARCHITECTURE.md ("Lane shaders") lists them and what the pipeline uses instead.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"

// Lane code is forced inline for speed: a lane function left out of line is compiled for the baseline only.
#define FACET_LANES_INLINE [[gnu::always_inline]] inline

namespace facet::simd {

// One strip of an 8x8 block: two rows of eight pixels, i.e. four 2x2 quads. Lane k is pixel (k % 8, k / 8).
inline constexpr int kLanes = 16;
inline constexpr std::size_t kLaneAlign = kLanes * sizeof(float);

// How the 16 lanes are held: as kParts native vectors of kLanes / kParts lanes each, lanes in order, so every
// layout has the same bytes in memory.
template <int kParts>
struct Layout {
  static_assert(kParts == 1 || kParts == 2 || kParts == 4);
  static constexpr int parts = kParts;
  static constexpr int width = kLanes / kParts;
};
using Whole = Layout<1>;     // one 512-bit vector: AVX-512
using Halves = Layout<2>;    // two 256-bit vectors, one per row of the strip: AVX2
using Quarters = Layout<4>;  // four 128-bit vectors: SSE, NEON, WebAssembly SIMD

// The bare vector types the lane types hold, for the pipeline's own use of compiler builtins on them.
namespace native {
template <class Scalar, int kWidth>
struct VectorOf;
// Spelled out per type and width: GCC 12 ignores vector_size on a dependent type.
#define FACET_NATIVE_VECTOR_(Scalar, kWidth)                               \
  template <>                                                              \
  struct VectorOf<Scalar, kWidth> {                                        \
    using type = Scalar __attribute__((vector_size(kWidth * sizeof(Scalar)))); \
  };
#define FACET_NATIVE_VECTORS_(Scalar) \
  FACET_NATIVE_VECTOR_(Scalar, 16) FACET_NATIVE_VECTOR_(Scalar, 8) FACET_NATIVE_VECTOR_(Scalar, 4)
FACET_NATIVE_VECTORS_(float)
FACET_NATIVE_VECTOR_(float, 2)  // a record of two floats (gather_records)
FACET_NATIVE_VECTORS_(std::int32_t)
FACET_NATIVE_VECTORS_(std::uint32_t)
#undef FACET_NATIVE_VECTORS_
#undef FACET_NATIVE_VECTOR_
template <class Scalar, int kWidth>
using Vector = typename VectorOf<Scalar, kWidth>::type;
using Float = Vector<float, kLanes>;
using Int = Vector<std::int32_t, kLanes>;
using UInt = Vector<std::uint32_t, kLanes>;
}  // namespace native

// Sixteen lanes of one scalar type, with the vector's operators, element-wise, and with a scalar on either side.
// Two things make a lane type safe wherever a shader author puts it:
// - its destructor is user-provided, so the type is not trivially copyable and every ABI passes and returns it
//   through memory by reference. A bare vector travels in registers between functions compiled for a level that has
//   them and in memory between baseline ones, so a helper left out of line (compiled for the baseline) and called
//   from a level's copy of the tile loop would read garbage. Inlined, the difference vanishes.
// - it is alignas(64) in every ISA and layout, so that lane values allocated by baseline code suit the aligned
//   loads of every level's copy.
template <class Scalar, class L>
class alignas(kLaneAlign) Lanes {
 public:
  using scalar_type = Scalar;
  using layout = L;
  static constexpr int kParts = L::parts, kWidth = L::width;
  using Part = native::Vector<Scalar, kWidth>;
  Part part[kParts];

  Lanes() = default;
  FACET_LANES_INLINE constexpr Lanes(Part v) requires(kParts == 1) : part{v} {}
  Lanes(const Lanes&) = default;
  Lanes& operator=(const Lanes&) = default;
  // User-provided, so that the type is not trivially copyable (see above). A destructor rather than a copy
  // constructor: with a user-provided copy, GCC 12 spills far more of the tile loop's vectors (4-sample frames of
  // sphere:224 a third slower); with this destructor, frames take the time bare vectors take.
  FACET_LANES_INLINE constexpr ~Lanes() {}

  // The lanes whose part i is op(i): each operation is one native operation per part.
  template <class R = Lanes, class Op>
  FACET_LANES_INLINE static constexpr R by_part(Op op) {
    R r;
    r.part[0] = op(0);
    if constexpr (kParts > 1) r.part[1] = op(1);
    if constexpr (kParts > 2) r.part[2] = op(2), r.part[3] = op(3);
    return r;
  }

  FACET_LANES_INLINE constexpr Scalar operator[](int k) const { return part[k / kWidth][k % kWidth]; }
#if defined(__clang__)
  // Clang binds no reference to a vector element; the element type may alias the vector.
  FACET_LANES_INLINE Scalar& operator[](int k) { return reinterpret_cast<Scalar*>(part)[k]; }
#else
  FACET_LANES_INLINE Scalar& operator[](int k) { return part[k / kWidth][k % kWidth]; }
#endif

// The operators spell out each part, R r's part i being EXPR, rather than calling by_part with a lambda: they are
// most of what lane code instantiates, and a lambda per operator and type cost a tenth more compile time.
#define FACET_LANES_BY_PART_(R, EXPR)            \
  R r;                                           \
  {                                              \
    constexpr int i = 0;                         \
    r.part[i] = EXPR;                            \
  }                                              \
  if constexpr (kParts > 1) {                    \
    constexpr int i = 1;                         \
    r.part[i] = EXPR;                            \
  }                                              \
  if constexpr (kParts > 2) {                    \
    constexpr int i = 2;                         \
    r.part[i] = EXPR;                            \
  }                                              \
  if constexpr (kParts > 3) {                    \
    constexpr int i = 3;                         \
    r.part[i] = EXPR;                            \
  }                                              \
  return r

  FACET_LANES_INLINE friend constexpr Lanes operator-(const Lanes& a) { FACET_LANES_BY_PART_(Lanes, -a.part[i]); }
  FACET_LANES_INLINE friend constexpr Lanes operator~(const Lanes& a) { FACET_LANES_BY_PART_(Lanes, ~a.part[i]); }

// The three forms of a binary operator giving R: two lane values, or a scalar on either side.
#define FACET_LANES_BINARY_(R, op)                                                                        \
  FACET_LANES_INLINE friend constexpr R operator op(const Lanes& a, const Lanes& b) {                      \
    FACET_LANES_BY_PART_(R, a.part[i] op b.part[i]);                                                       \
  }                                                                                                        \
  FACET_LANES_INLINE friend constexpr R operator op(const Lanes& a, Scalar b) {                            \
    FACET_LANES_BY_PART_(R, a.part[i] op b);                                                               \
  }                                                                                                        \
  FACET_LANES_INLINE friend constexpr R operator op(Scalar a, const Lanes& b) {                            \
    FACET_LANES_BY_PART_(R, a op b.part[i]);                                                               \
  }
#define FACET_LANES_OPERATOR(op)                                                                           \
  FACET_LANES_BINARY_(Lanes, op)                                                                            \
  FACET_LANES_INLINE constexpr Lanes& operator op##=(const Lanes& b) { return *this = *this op b; }         \
  FACET_LANES_INLINE constexpr Lanes& operator op##=(Scalar b) { return *this = *this op b; }
  FACET_LANES_OPERATOR(+)
  FACET_LANES_OPERATOR(-)
  FACET_LANES_OPERATOR(*)
  FACET_LANES_OPERATOR(/)
  FACET_LANES_OPERATOR(%)
  FACET_LANES_OPERATOR(&)
  FACET_LANES_OPERATOR(|)
  FACET_LANES_OPERATOR(^)
  FACET_LANES_OPERATOR(<<)
  FACET_LANES_OPERATOR(>>)
#undef FACET_LANES_OPERATOR

  // Comparisons give a mask per lane: -1 where true, 0 where false.
  using MaskType = Lanes<std::int32_t, L>;
  FACET_LANES_BINARY_(MaskType, ==)
  FACET_LANES_BINARY_(MaskType, !=)
  FACET_LANES_BINARY_(MaskType, <)
  FACET_LANES_BINARY_(MaskType, <=)
  FACET_LANES_BINARY_(MaskType, >)
  FACET_LANES_BINARY_(MaskType, >=)
#undef FACET_LANES_BINARY_
#undef FACET_LANES_BY_PART_
};

// The lane types of a layout. Comparisons of FloatT or IntT give an IntT mask per lane: -1 where true, 0 where false.
template <class L>
using FloatT = Lanes<float, L>;
template <class L>
using IntT = Lanes<std::int32_t, L>;
template <class L>
using UIntT = Lanes<std::uint32_t, L>;
template <class L>
using MaskT = IntT<L>;

using Float = FloatT<Whole>;
using Int = IntT<Whole>;
using UInt = UIntT<Whole>;
using Mask = Int;

// The lane numbers 0..15, as lane values of a layout.
template <class L>
inline constexpr IntT<L> kLaneIndexT = IntT<L>::by_part([](int i) {
  return [&]<int... k>(std::integer_sequence<int, k...>) {
    return typename IntT<L>::Part{(i * L::width + k)...};
  }(std::make_integer_sequence<int, L::width>{});
});
template <class L>
inline constexpr IntT<L> kLaneXT = kLaneIndexT<L> & 7;
template <class L>
inline constexpr IntT<L> kLaneYT = kLaneIndexT<L> >> 3;
inline constexpr Int kLaneIndex = kLaneIndexT<Whole>;
inline constexpr Int kLaneX = kLaneXT<Whole>;
inline constexpr Int kLaneY = kLaneYT<Whole>;

// v - 0 rather than 0 + v: subtracting +0 leaves every value as it is (-0 included), so GCC folds it into a plain
// broadcast (or a broadcast memory operand); adding +0 turns -0 into +0, so it cannot, and each splat of a
// run-time value would cost an addition and a separate broadcast. Meant for constants: a run-time value is better
// left a scalar operand (`a * v`, `uniform - v`, see Vec3T below), since its splat, once a struct member, is built
// lane by lane in the AVX-512 copy.
template <class L = Whole>
FACET_LANES_INLINE FloatT<L> splat(float v) {
  return FloatT<L>::by_part([&](int) __attribute__((always_inline)) { return v - typename FloatT<L>::Part{}; });
}
template <class L = Whole>
FACET_LANES_INLINE IntT<L> splat(std::int32_t v) {
  return IntT<L>::by_part([&](int) __attribute__((always_inline)) { return typename IntT<L>::Part{} + v; });
}

template <class L>
FACET_LANES_INLINE FloatT<L> select(const MaskT<L>& m, const FloatT<L>& a, const FloatT<L>& b) {
  return FloatT<L>::by_part([&](int i) __attribute__((always_inline)) { return m.part[i] ? a.part[i] : b.part[i]; });
}
// The same bits read as another lane type of the same layout (std::bit_cast for lanes).
template <class To, class Scalar, class L>
FACET_LANES_INLINE To bit_cast(const Lanes<Scalar, L>& v) {
  static_assert(std::is_same_v<typename To::layout, L>);
  return To::by_part([&](int i) __attribute__((always_inline)) {
    return reinterpret_cast<typename To::Part>(v.part[i]);
  });
}
// Lanes of a where m is -1, of b where it is 0, by bitwise operations: exact for any bit pattern, and immune to
// GCC 12 scalarising `m ? a : b` for a mask that was not itself a comparison.
template <class Scalar, class L>
FACET_LANES_INLINE Lanes<Scalar, L> blend(const MaskT<L>& m, const Lanes<Scalar, L>& a, const Lanes<Scalar, L>& b) {
  return bit_cast<Lanes<Scalar, L>>((bit_cast<IntT<L>>(a) & m) | (bit_cast<IntT<L>>(b) & ~m));
}
// std::clamp's comparisons, so NaN and the bounds behave exactly as in the scalar paths.
template <class L>
FACET_LANES_INLINE FloatT<L> clamp(const FloatT<L>& v, float lo, float hi) {
  return select(v < lo, splat<L>(lo), select(hi < v, splat<L>(hi), v));
}

// op on each 128-bit quarter of the lanes, in memory order.
template <class Scalar, class L, class Op>
FACET_LANES_INLINE Lanes<Scalar, L> by_quarter(Lanes<Scalar, L> v, Op op) {
  using Quarter = native::Vector<Scalar, 4>;
  Quarter quarters[kLanes / 4];
  std::memcpy(quarters, v.part, sizeof quarters);
  for (Quarter& q : quarters) q = op(q);
  std::memcpy(v.part, quarters, sizeof quarters);
  return v;
}

#if defined(__wasm_simd128__)
// WebAssembly: Clang leaves plain loops over the lanes scalar there, so each quarter takes one instruction.
template <class L>
FACET_LANES_INLINE FloatT<L> sqrt(const FloatT<L>& v) {
  return by_quarter(v, [](auto q) { return reinterpret_cast<decltype(q)>(wasm_f32x4_sqrt(q)); });
}
template <class L>
FACET_LANES_INLINE FloatT<L> floor(const FloatT<L>& v) {
  return by_quarter(v, [](auto q) { return reinterpret_cast<decltype(q)>(wasm_f32x4_floor(q)); });
}
#else
// A plain loop over each part's lanes: with -fno-math-errno (set for every facet user) it compiles to one vector
// sqrt per part.
template <class L>
FACET_LANES_INLINE FloatT<L> sqrt(const FloatT<L>& v) {
  return FloatT<L>::by_part([&](int i) __attribute__((always_inline)) {
    typename FloatT<L>::Part r;
    for (int k = 0; k < L::width; ++k) r[k] = std::sqrt(v.part[i][k]);
    return r;
  });
}
// Like sqrt: one rounding instruction per part where the level has one (SSE4.1 and later, NEON). The 128-bit
// layout on x86-64 is the baseline's (SSE2, which has none, and GCC 12 rounds lane by lane there), so it rounds by
// conversion: the truncation, less one where it rounded up; values of 2^23 and more (already whole) and NaN as
// they are; and the sign bit of the input kept, so that -0 stays -0. Exactly std::floor.
template <class L>
FACET_LANES_INLINE FloatT<L> floor(const FloatT<L>& v) {
#if defined(__x86_64__)
  if constexpr (L::parts == 4) {
    const IntT<L> bits = bit_cast<IntT<L>>(v), sign = bits & static_cast<std::int32_t>(0x80000000u);
    const MaskT<L> small = bit_cast<FloatT<L>>(bits ^ sign) < 8388608.0f;
    const FloatT<L> in_range = bit_cast<FloatT<L>>(bits & small);  // 0 elsewhere: no conversion overflows
    const FloatT<L> truncated = to_float(truncate(in_range));
    const FloatT<L> lower =
        truncated - bit_cast<FloatT<L>>((truncated > in_range) & bit_cast<IntT<L>>(splat<L>(1.0f)));
    return bit_cast<FloatT<L>>(blend(small, bit_cast<IntT<L>>(lower) | sign, bits));
  }
#endif
  return FloatT<L>::by_part([&](int i) __attribute__((always_inline)) {
    typename FloatT<L>::Part r;
    for (int k = 0; k < L::width; ++k) r[k] = std::floor(v.part[i][k]);
    return r;
  });
}
#endif

// The value at base[index[k]] in each lane k, loaded lane by lane: facet builds without gather instructions
// (docs/ARCHITECTURE.md, "Physically based shading", says why). Records of two or four floats are read faster
// by gather_records (simd_shuffles.hpp).
template <class L>
FACET_LANES_INLINE FloatT<L> gather(const float* base, const IntT<L>& index) {
  FloatT<L> out;
  for (int k = 0; k < kLanes; ++k) out[k] = base[index[k]];
  return out;
}

// Value conversions between the lane types, as static_cast does them.
template <class To, class Scalar, class L>
FACET_LANES_INLINE To convert(const Lanes<Scalar, L>& v) {
  return To::by_part([&](int i) __attribute__((always_inline)) {
    return __builtin_convertvector(v.part[i], typename To::Part);
  });
}
template <class L>
FACET_LANES_INLINE FloatT<L> to_float(const IntT<L>& v) { return convert<FloatT<L>>(v); }
template <class L>
FACET_LANES_INLINE IntT<L> truncate(const FloatT<L>& v) { return convert<IntT<L>>(v); }
template <class L>
FACET_LANES_INLINE IntT<L> to_int(const UIntT<L>& v) { return convert<IntT<L>>(v); }
template <class L>
FACET_LANES_INLINE UIntT<L> to_uint(const IntT<L>& v) { return convert<UIntT<L>>(v); }

// 16 lanes from memory, or to it, at any alignment: part by part, so that each part goes straight to or from its
// register (a copy of the whole array leaves GCC 12 copying through the stack).
template <class V>
FACET_LANES_INLINE V load(const void* p) {
  return V::by_part([&](int i) __attribute__((always_inline)) {
    typename V::Part part;
    std::memcpy(&part, static_cast<const char*>(p) + i * sizeof part, sizeof part);
    return part;
  });
}
template <class V>
FACET_LANES_INLINE void store(void* p, const V& v) {
  for (int i = 0; i < V::kParts; ++i)
    std::memcpy(static_cast<char*>(p) + i * sizeof v.part[i], &v.part[i], sizeof v.part[i]);
}

// Bit k set where lane k of m is -1 (true).
template <class L>
FACET_LANES_INLINE unsigned lane_bits(const MaskT<L>& m) {
#if defined(__wasm_simd128__)
  v128_t quarters[kLanes / 4];
  std::memcpy(quarters, m.part, sizeof quarters);
  unsigned bits = 0;
  for (int q = 0; q < kLanes / 4; ++q) bits |= static_cast<unsigned>(wasm_i32x4_bitmask(quarters[q])) << (4 * q);
  return bits;
#else
#if defined(__SSE2__)
  // GCC 12's vectoriser leaves the loop below scalar for 128-bit parts, and makes it a chain of shifts and ors for
  // 256-bit ones: one SSE movmskps per 128 bits instead (the AVX one would not compile in the baseline code that
  // may use a layout of halves too).
  if constexpr (L::width <= 8) {
    using Quarter = native::Vector<float, 4>;
    Quarter quarters[kLanes / 4];
    std::memcpy(quarters, m.part, sizeof quarters);
    unsigned bits = 0;
    for (int q = 0; q < kLanes / 4; ++q)
      bits |= static_cast<unsigned>(__builtin_ia32_movmskps(quarters[q])) << (4 * q);
    return bits;
  }
#endif
  unsigned bits = 0;
  for (int i = 0; i < L::parts; ++i) {
#pragma GCC unroll 1  // a loop for the vectoriser: one mask extraction at each level
    for (int k = 0; k < L::width; ++k) bits |= static_cast<unsigned>(m.part[i][k] & 1) << (i * L::width + k);
  }
  return bits;
#endif
}

}  // namespace facet::simd

#include "facet/simd_shuffles.hpp"
#include "facet/simd_vectors.hpp"

#pragma GCC diagnostic pop
