// simd_vectors.hpp - 2- and 3-vectors and colours of lane values, and their maths with uniform glm vectors.
#pragma once

#include <glm/vec3.hpp>

#include "facet/simd.hpp"

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"

namespace facet::simd {

template <class L>
struct alignas(kLaneAlign) Vec2T {
  FloatT<L> x, y;
};

template <class L>
struct alignas(kLaneAlign) Vec3T {
  FloatT<L> x, y, z;
  FACET_LANES_INLINE friend Vec3T operator+(const Vec3T& a, const Vec3T& b) {
    return {a.x + b.x, a.y + b.y, a.z + b.z};
  }
  FACET_LANES_INLINE friend Vec3T operator-(const Vec3T& a, const Vec3T& b) {
    return {a.x - b.x, a.y - b.y, a.z - b.z};
  }
  FACET_LANES_INLINE friend Vec3T operator*(const Vec3T& a, const FloatT<L>& s) { return {a.x * s, a.y * s, a.z * s}; }
  FACET_LANES_INLINE friend Vec3T operator*(const FloatT<L>& s, const Vec3T& a) { return {s * a.x, s * a.y, s * a.z}; }
  // A uniform vector with a lane vector: the uniform's components stay scalar operands of each operation. A Vec3
  // of splats of run-time values would be built lane by lane in the AVX-512 copy (16 masked inserts per member:
  // GCC 12 lowers the splat for the baseline before the level's copy exists); a scalar operand becomes one
  // broadcast.
  FACET_LANES_INLINE friend Vec3T operator-(const glm::vec3& a, const Vec3T& b) {
    return {a.x - b.x, a.y - b.y, a.z - b.z};
  }
  FACET_LANES_INLINE friend Vec3T operator-(const Vec3T& a, const glm::vec3& b) {
    return {a.x - b.x, a.y - b.y, a.z - b.z};
  }
  FACET_LANES_INLINE friend Vec3T operator+(const Vec3T& a, const glm::vec3& b) {
    return {a.x + b.x, a.y + b.y, a.z + b.z};
  }
};

// In glm's order, (x*x + y*y) + z*z, so lane and scalar shaders round alike.
template <class L>
FACET_LANES_INLINE FloatT<L> dot(const Vec3T<L>& a, const Vec3T<L>& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
template <class L>
FACET_LANES_INLINE FloatT<L> dot(const Vec3T<L>& a, const glm::vec3& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
template <class L>
FACET_LANES_INLINE Vec3T<L> normalize(const Vec3T<L>& v) {
  return v * (1.0f / sqrt(dot(v, v)));
}

// What a lane fragment shader returns: straight (not premultiplied) RGBA in [0, 1].
template <class L>
struct alignas(kLaneAlign) ColorT {
  FloatT<L> r, g, b, a;
};

using Vec2 = Vec2T<Whole>;
using Vec3 = Vec3T<Whole>;
using Color = ColorT<Whole>;

// In a template on a lane layout L, the layout's types by their layout-free names: Float, Int, UInt, Mask, Vec2,
// Vec3 and Color.
#define FACET_LANE_TYPES(L)                   \
  using Float [[maybe_unused]] = ::facet::simd::FloatT<L>;     \
  using Int [[maybe_unused]] = ::facet::simd::IntT<L>;         \
  using UInt [[maybe_unused]] = ::facet::simd::UIntT<L>;       \
  using Mask [[maybe_unused]] = ::facet::simd::MaskT<L>;       \
  using Vec2 [[maybe_unused]] = ::facet::simd::Vec2T<L>;       \
  using Vec3 [[maybe_unused]] = ::facet::simd::Vec3T<L>;       \
  using Color [[maybe_unused]] = ::facet::simd::ColorT<L>

// pack_rgba8 per lane: clamp to [0, 1] (NaN to 0), scale to 255 and round to nearest.
template <class L>
FACET_LANES_INLINE UIntT<L> pack_channel(const FloatT<L>& c) {
  const FloatT<L> clamped = select(c > 0.0f, select(c < 1.0f, c, splat<L>(1.0f)), splat<L>(0.0f));
  return to_uint(truncate(clamped * 255.0f + 0.5f));
}
template <class L>
FACET_LANES_INLINE UIntT<L> pack_rgba8(const ColorT<L>& c) {
  return pack_channel(c.r) | pack_channel(c.g) << 8 | pack_channel(c.b) << 16 | pack_channel(c.a) << 24;
}

}  // namespace facet::simd

#pragma GCC diagnostic pop
