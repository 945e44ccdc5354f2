// simd.hpp - 16-lane float and int types for shading a strip of fragments at once, and the lane maths shaders use.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>

#include <glm/vec3.hpp>
#if defined(__wasm_simd128__)
#include <wasm_simd128.h>
#endif

// The lane types wrap GCC/Clang vector extensions rather than intrinsics: the compiler lowers each operation for
// the instruction set of the function it ends up in (each CPU level's copy, detail/dispatch.hpp), so the same shader
// code becomes one AVX-512 instruction in the x86-64-v4 copy of the tile loop, two AVX2 or four SSE instructions
// below it and four WebAssembly SIMD instructions in the browser build. Below AVX-512, GCC 12 has no mode for a
// 64-byte vector and keeps each value in memory between operations (docs/PERFORMANCE.md, "Every CPU level").
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

// The bare vector types the lane types hold, for the pipeline's own use of compiler builtins on them.
namespace native {
using Float = float __attribute__((vector_size(kLanes * sizeof(float))));
using Int = std::int32_t __attribute__((vector_size(kLanes * sizeof(std::int32_t))));
using UInt = std::uint32_t __attribute__((vector_size(kLanes * sizeof(std::uint32_t))));
}  // namespace native

// Sixteen lanes of one scalar type, with the vector's operators, element-wise, and with a scalar on either side.
// Two things make a lane type safe wherever a shader author puts it:
// - its destructor is user-provided, so the type is not trivially copyable and every ABI passes and returns it
//   through memory by reference. A bare 64-byte vector travels in a zmm register between functions compiled for
//   AVX-512 and in memory between baseline ones, so a helper left out of line (compiled for the baseline) and
//   called from the AVX-512 copy of the tile loop would read garbage. Inlined, the difference vanishes.
// - it is alignas(64) in every ISA. GCC aligns a bare 64-byte vector to the widest vector of the code that names
//   it (16 bytes in the baseline), so lane values allocated by baseline code would be under-aligned for the
//   aligned loads of the AVX-512 copy.
template <class Native, class Scalar>
class alignas(kLaneAlign) Lanes {
 public:
  using scalar_type = Scalar;
  Native native;

  Lanes() = default;
  FACET_LANES_INLINE constexpr Lanes(Native v) : native(v) {}
  Lanes(const Lanes&) = default;
  Lanes& operator=(const Lanes&) = default;
  // User-provided, so that the type is not trivially copyable (see above). A destructor rather than a copy
  // constructor: with a user-provided copy, GCC 12 spills far more of the tile loop's vectors (4-sample frames of
  // sphere:224 a third slower); with this destructor, frames take the time bare vectors take.
  FACET_LANES_INLINE constexpr ~Lanes() {}

  FACET_LANES_INLINE constexpr Scalar operator[](int k) const { return native[k]; }
#if defined(__clang__)
  // Clang binds no reference to a vector element; the element type may alias the vector.
  FACET_LANES_INLINE Scalar& operator[](int k) { return reinterpret_cast<Scalar*>(&native)[k]; }
#else
  FACET_LANES_INLINE Scalar& operator[](int k) { return native[k]; }
#endif

  FACET_LANES_INLINE friend constexpr Lanes operator-(const Lanes& a) { return -a.native; }
  FACET_LANES_INLINE friend constexpr Lanes operator~(const Lanes& a) { return ~a.native; }

#define FACET_LANES_OPERATOR(op)                                                                                  \
  FACET_LANES_INLINE friend constexpr Lanes operator op(const Lanes& a, const Lanes& b) {                          \
    return a.native op b.native;                                                                                   \
  }                                                                                                                \
  FACET_LANES_INLINE friend constexpr Lanes operator op(const Lanes& a, Scalar b) { return a.native op b; }        \
  FACET_LANES_INLINE friend constexpr Lanes operator op(Scalar a, const Lanes& b) { return a op b.native; }        \
  FACET_LANES_INLINE constexpr Lanes& operator op##=(const Lanes& b) {                                             \
    native = native op b.native;                                                                                   \
    return *this;                                                                                                  \
  }                                                                                                                \
  FACET_LANES_INLINE constexpr Lanes& operator op##=(Scalar b) {                                                   \
    native = native op b;                                                                                          \
    return *this;                                                                                                  \
  }
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
  using MaskType = Lanes<native::Int, std::int32_t>;
#define FACET_LANES_COMPARISON(op)                                                                                \
  FACET_LANES_INLINE friend constexpr MaskType operator op(const Lanes& a, const Lanes& b) {                       \
    return a.native op b.native;                                                                                   \
  }                                                                                                                \
  FACET_LANES_INLINE friend constexpr MaskType operator op(const Lanes& a, Scalar b) { return a.native op b; }     \
  FACET_LANES_INLINE friend constexpr MaskType operator op(Scalar a, const Lanes& b) { return a op b.native; }
  FACET_LANES_COMPARISON(==)
  FACET_LANES_COMPARISON(!=)
  FACET_LANES_COMPARISON(<)
  FACET_LANES_COMPARISON(<=)
  FACET_LANES_COMPARISON(>)
  FACET_LANES_COMPARISON(>=)
#undef FACET_LANES_COMPARISON
};

using Float = Lanes<native::Float, float>;
using Int = Lanes<native::Int, std::int32_t>;
using UInt = Lanes<native::UInt, std::uint32_t>;
// Comparisons of Float or Int give an Int mask per lane: -1 where true, 0 where false.
using Mask = Int;

inline constexpr Int kLaneIndex = native::Int{0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15};
inline constexpr Int kLaneX = kLaneIndex & 7;
inline constexpr Int kLaneY = kLaneIndex >> 3;

// v - 0 rather than 0 + v: subtracting +0 leaves every value as it is (-0 included), so GCC folds it into a plain
// broadcast (or a broadcast memory operand); adding +0 turns -0 into +0, so it cannot, and each splat of a
// run-time value would cost an addition and a separate broadcast. Meant for constants: a run-time value is better
// left a scalar operand (`a * v`, `uniform - v`, see Vec3 below), since its splat, once a struct member, is built
// lane by lane in the AVX-512 copy.
FACET_LANES_INLINE Float splat(float v) { return v - native::Float{}; }
FACET_LANES_INLINE Int splat(std::int32_t v) { return native::Int{} + v; }

FACET_LANES_INLINE Float select(const Mask& m, const Float& a, const Float& b) { return m.native ? a.native : b.native; }
// Lanes of a where m is -1, of b where it is 0, by bitwise operations: exact for any bit pattern, and immune to
// GCC 12 scalarising `m ? a : b` for a mask that was not itself a comparison.
template <class V>
FACET_LANES_INLINE V blend(const Mask& m, const V& a, const V& b) {
  using N = decltype(V::native);
  return reinterpret_cast<N>((reinterpret_cast<native::Int>(a.native) & m.native) |
                             (reinterpret_cast<native::Int>(b.native) & ~m.native));
}
// The same bits read as another lane type (std::bit_cast for lanes).
template <class To, class From>
FACET_LANES_INLINE To bit_cast(const From& v) {
  return reinterpret_cast<decltype(To::native)>(v.native);
}
// std::clamp's comparisons, so NaN and the bounds behave exactly as in the scalar paths.
FACET_LANES_INLINE Float clamp(Float v, float lo, float hi) {
  return select(v < lo, splat(lo), select(hi < v, splat(hi), v));
}

#if defined(__wasm_simd128__)
// WebAssembly: Clang leaves the plain loops below scalar there, so each quarter of the lanes takes one instruction.
template <class Op>
FACET_LANES_INLINE Float by_quarter(Float v, Op op) {
  v128_t quarters[kLanes / 4];
  std::memcpy(quarters, &v.native, sizeof v.native);
  for (v128_t& q : quarters) q = op(q);
  std::memcpy(&v.native, quarters, sizeof v.native);
  return v;
}
FACET_LANES_INLINE Float sqrt(Float v) {
  return by_quarter(v, [](v128_t q) { return wasm_f32x4_sqrt(q); });
}
FACET_LANES_INLINE Float floor(Float v) {
  return by_quarter(v, [](v128_t q) { return wasm_f32x4_floor(q); });
}
#else
// A plain loop over the lanes: with -fno-math-errno (set for every facet user) it compiles to one vector sqrt.
FACET_LANES_INLINE Float sqrt(Float v) {
  native::Float r;
  for (int k = 0; k < kLanes; ++k) r[k] = std::sqrt(v.native[k]);
  return r;
}

// A plain loop over the lanes, like sqrt: one rounding instruction where the level has one (SSE4.1 and later).
FACET_LANES_INLINE Float floor(Float v) {
  native::Float r;
  for (int k = 0; k < kLanes; ++k) r[k] = std::floor(v.native[k]);
  return r;
}
#endif

// The value at base[index[k]] in each lane k, loaded lane by lane: facet builds without gather instructions
// (docs/ARCHITECTURE.md, "Physically based shading", says why), so tables and texels are read this way.
FACET_LANES_INLINE Float gather(const float* base, const Int& index) {
  Float out;
  for (int k = 0; k < kLanes; ++k) out[k] = base[index[k]];
  return out;
}

FACET_LANES_INLINE Float to_float(const Int& v) { return __builtin_convertvector(v.native, native::Float); }
FACET_LANES_INLINE Int truncate(const Float& v) { return __builtin_convertvector(v.native, native::Int); }
// Value conversions between the integer lane types, as static_cast does them.
FACET_LANES_INLINE Int to_int(const UInt& v) { return __builtin_convertvector(v.native, native::Int); }
FACET_LANES_INLINE UInt to_uint(const Int& v) { return __builtin_convertvector(v.native, native::UInt); }

template <class V>
FACET_LANES_INLINE V load(const void* p) {
  V v;
  std::memcpy(&v.native, p, sizeof v.native);
  return v;
}
template <class V>
FACET_LANES_INLINE void store(void* p, const V& v) {
  std::memcpy(p, &v.native, sizeof v.native);
}

// Lane k of the result is lane pattern[k] of v, or of the lanes of a followed by those of b. GCC spells this
// __builtin_shuffle; Clang has only __builtin_shufflevector with literal indices, so its build uses a loop, which
// it folds into one shuffle for the constant patterns facet passes.
#if defined(__clang__)
template <class V>
FACET_LANES_INLINE V shuffle(const V& v, const Int& pattern) {
  decltype(V::native) r;
  for (int k = 0; k < kLanes; ++k) r[k] = v.native[pattern.native[k] & (kLanes - 1)];
  return r;
}
template <class V>
FACET_LANES_INLINE V shuffle(const V& a, const V& b, const Int& pattern) {
  decltype(V::native) r;
  for (int k = 0; k < kLanes; ++k) {
    const int i = pattern.native[k] & (2 * kLanes - 1);
    r[k] = i < kLanes ? a.native[i] : b.native[i - kLanes];
  }
  return r;
}
#else
template <class V>
FACET_LANES_INLINE V shuffle(const V& v, const Int& pattern) {
  return __builtin_shuffle(v.native, pattern.native);
}
template <class V>
FACET_LANES_INLINE V shuffle(const V& a, const V& b, const Int& pattern) {
  return __builtin_shuffle(a.native, b.native, pattern.native);
}
#endif

// Bit k set where lane k of m is -1 (true).
FACET_LANES_INLINE unsigned lane_bits(const Mask& m) {
#if defined(__wasm_simd128__)
  v128_t quarters[kLanes / 4];
  std::memcpy(quarters, &m.native, sizeof m.native);
  unsigned bits = 0;
  for (int q = 0; q < kLanes / 4; ++q) bits |= static_cast<unsigned>(wasm_i32x4_bitmask(quarters[q])) << (4 * q);
  return bits;
#else
  unsigned bits = 0;
#pragma GCC unroll 1  // a loop for the vectoriser: one mask extraction at each level
  for (int k = 0; k < kLanes; ++k) bits |= static_cast<unsigned>(m.native[k] & 1) << k;
  return bits;
#endif
}

// Swaps lanes within each 2x2 quad: coarse derivatives are differences between a quad's pixels.
FACET_LANES_INLINE Float quad_broadcast(Float v, Int pattern) { return shuffle(v, pattern); }
inline constexpr Int kQuadTopLeft = (kLaneIndex & ~9);         // lane of each quad's (0, 0) pixel
inline constexpr Int kQuadTopRight = (kLaneIndex & ~9) | 1;    // ... (1, 0)
inline constexpr Int kQuadBottomLeft = (kLaneIndex & ~9) | 8;  // ... (0, 1)

struct alignas(kLaneAlign) Vec2 {
  Float x, y;
};

struct alignas(kLaneAlign) Vec3 {
  Float x, y, z;
  FACET_LANES_INLINE friend Vec3 operator+(const Vec3& a, const Vec3& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
  FACET_LANES_INLINE friend Vec3 operator-(const Vec3& a, const Vec3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
  FACET_LANES_INLINE friend Vec3 operator*(const Vec3& a, Float s) { return {a.x * s, a.y * s, a.z * s}; }
  FACET_LANES_INLINE friend Vec3 operator*(Float s, const Vec3& a) { return {s * a.x, s * a.y, s * a.z}; }
};

// A uniform vector with a lane vector: the uniform's components stay scalar operands of each operation. A Vec3 of
// splats of run-time values would be built lane by lane in the AVX-512 copy (16 masked inserts per member: GCC 12
// lowers the splat for the baseline before the level's copy exists); a scalar operand becomes one broadcast.
FACET_LANES_INLINE Vec3 operator-(const glm::vec3& a, const Vec3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
FACET_LANES_INLINE Vec3 operator-(const Vec3& a, const glm::vec3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
FACET_LANES_INLINE Vec3 operator+(const Vec3& a, const glm::vec3& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
// In glm's order, (x*x + y*y) + z*z, so lane and scalar shaders round alike.
FACET_LANES_INLINE Float dot(const Vec3& a, const Vec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
FACET_LANES_INLINE Float dot(const Vec3& a, const glm::vec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
FACET_LANES_INLINE Vec3 normalize(const Vec3& v) { return v * (1.0f / sqrt(dot(v, v))); }

// What a lane fragment shader returns: straight (not premultiplied) RGBA in [0, 1].
struct alignas(kLaneAlign) Color {
  Float r, g, b, a;
};

// pack_rgba8 per lane: clamp to [0, 1] (NaN to 0), scale to 255 and round to nearest.
FACET_LANES_INLINE UInt pack_channel(Float c) {
  const Float clamped = select(c > 0.0f, select(c < 1.0f, c, splat(1.0f)), splat(0.0f));
  return to_uint(truncate(clamped * 255.0f + 0.5f));
}
FACET_LANES_INLINE UInt pack_rgba8(const Color& c) {
  return pack_channel(c.r) | pack_channel(c.g) << 8 | pack_channel(c.b) << 16 | pack_channel(c.a) << 24;
}

}  // namespace facet::simd

#pragma GCC diagnostic pop
