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

// The lane types are GCC/Clang vector extensions rather than intrinsics: the compiler lowers each operation for
// the instruction set of the function it ends up in, so the same shader code becomes one AVX-512 instruction in
// the x86-64-v4 clone of the tile loop, two AVX2 instructions in the v3 clone, four SSE2 instructions in the
// baseline (see detail/dispatch.hpp) and four WebAssembly SIMD instructions in the browser build. Passing such vectors by value between functions compiled for different
// ISAs would change the ABI, hence -Wpsabi is silenced here and everything is always inlined. GCC 12 lowers a
// few idioms element by element when they are inlined from the baseline into a clone; docs/ARCHITECTURE.md
// ("Lane shaders") lists them and what the pipeline uses instead.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"

#define FACET_LANES_INLINE [[gnu::always_inline]] inline

namespace facet::simd {

// One strip of an 8x8 block: two rows of eight pixels, i.e. four 2x2 quads. Lane k is pixel (k % 8, k / 8).
inline constexpr int kLanes = 16;

using Float = float __attribute__((vector_size(kLanes * sizeof(float))));
using Int = std::int32_t __attribute__((vector_size(kLanes * sizeof(std::int32_t))));
using UInt = std::uint32_t __attribute__((vector_size(kLanes * sizeof(std::uint32_t))));
// GCC aligns a 64-byte vector type to the widest vector of the code that names it: 64 bytes inside the AVX-512
// clone, 16 in the baseline. A FragmentLanes allocated in baseline code (in a std::vector, say) would then be
// under-aligned for the aligned loads the clone emits, so every struct of lane values states its alignment.
inline constexpr std::size_t kLaneAlign = kLanes * sizeof(float);
// Comparisons of Float or Int give an Int mask per lane: -1 where true, 0 where false.
using Mask = Int;

inline constexpr Int kLaneIndex = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15};
inline constexpr Int kLaneX = kLaneIndex & 7;
inline constexpr Int kLaneY = kLaneIndex >> 3;

// v - 0 rather than 0 + v: subtracting +0 leaves every value as it is (-0 included), so GCC folds it into a plain
// broadcast (or a broadcast memory operand); adding +0 turns -0 into +0, so it cannot, and each splat of a
// run-time value would cost an addition and a separate broadcast. Meant for constants: a run-time value is better
// left a scalar operand (`a * v`, `uniform - v`, see Vec3 below), since its splat, once a struct member, is built
// lane by lane in the AVX-512 clone.
FACET_LANES_INLINE Float splat(float v) { return v - Float{}; }
FACET_LANES_INLINE Int splat(std::int32_t v) { return Int{} + v; }

FACET_LANES_INLINE Float select(Mask m, Float a, Float b) { return m ? a : b; }
// Lanes of a where m is -1, of b where it is 0, by bitwise operations: exact for any bit pattern, and immune to
// GCC 12 scalarising `m ? a : b` for a mask that was not itself a comparison.
template <class V>
FACET_LANES_INLINE V blend(Mask m, V a, V b) {
  return reinterpret_cast<V>((reinterpret_cast<Int>(a) & m) | (reinterpret_cast<Int>(b) & ~m));
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
  std::memcpy(quarters, &v, sizeof v);
  for (v128_t& q : quarters) q = op(q);
  std::memcpy(&v, quarters, sizeof v);
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
  Float r;
  for (int k = 0; k < kLanes; ++k) r[k] = std::sqrt(v[k]);
  return r;
}

// A plain loop over the lanes, like sqrt: one rounding instruction where the clone has one (SSE4.1 and later).
FACET_LANES_INLINE Float floor(Float v) {
  Float r;
  for (int k = 0; k < kLanes; ++k) r[k] = std::floor(v[k]);
  return r;
}
#endif

FACET_LANES_INLINE Float to_float(Int v) { return __builtin_convertvector(v, Float); }
FACET_LANES_INLINE Int truncate(Float v) { return __builtin_convertvector(v, Int); }

template <class V>
FACET_LANES_INLINE V load(const void* p) {
  V v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
template <class V>
FACET_LANES_INLINE void store(void* p, const V& v) {
  std::memcpy(p, &v, sizeof v);
}

// Lane k of the result is lane pattern[k] of v, or of the lanes of a followed by those of b. GCC spells this
// __builtin_shuffle; Clang has only __builtin_shufflevector with literal indices, so its build uses a loop, which
// it folds into one shuffle for the constant patterns facet passes.
#if defined(__clang__)
template <class V>
FACET_LANES_INLINE V shuffle(V v, Int pattern) {
  V r;
  for (int k = 0; k < kLanes; ++k) r[k] = v[pattern[k] & (kLanes - 1)];
  return r;
}
template <class V>
FACET_LANES_INLINE V shuffle(V a, V b, Int pattern) {
  V r;
  for (int k = 0; k < kLanes; ++k) {
    const int i = pattern[k] & (2 * kLanes - 1);
    r[k] = i < kLanes ? a[i] : b[i - kLanes];
  }
  return r;
}
#else
template <class V>
FACET_LANES_INLINE V shuffle(V v, Int pattern) {
  return __builtin_shuffle(v, pattern);
}
template <class V>
FACET_LANES_INLINE V shuffle(V a, V b, Int pattern) {
  return __builtin_shuffle(a, b, pattern);
}
#endif

// Bit k set where lane k of m is -1 (true).
FACET_LANES_INLINE unsigned lane_bits(Mask m) {
#if defined(__wasm_simd128__)
  v128_t quarters[kLanes / 4];
  std::memcpy(quarters, &m, sizeof m);
  unsigned bits = 0;
  for (int q = 0; q < kLanes / 4; ++q) bits |= static_cast<unsigned>(wasm_i32x4_bitmask(quarters[q])) << (4 * q);
  return bits;
#else
  unsigned bits = 0;
#pragma GCC unroll 1  // a loop for the vectoriser: one mask extraction in each clone
  for (int k = 0; k < kLanes; ++k) bits |= static_cast<unsigned>(m[k] & 1) << k;
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
// splats of run-time values would be built lane by lane in the AVX-512 clone (16 masked inserts per member: GCC 12
// lowers the splat for the baseline before the clone exists); a scalar operand becomes one broadcast.
FACET_LANES_INLINE Vec3 operator-(const glm::vec3& a, const Vec3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
FACET_LANES_INLINE Vec3 operator-(const Vec3& a, const glm::vec3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
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
  return __builtin_convertvector(truncate(clamped * 255.0f + 0.5f), UInt);
}
FACET_LANES_INLINE UInt pack_rgba8(const Color& c) {
  return pack_channel(c.r) | pack_channel(c.g) << 8 | pack_channel(c.b) << 16 | pack_channel(c.a) << 24;
}

}  // namespace facet::simd

#pragma GCC diagnostic pop
