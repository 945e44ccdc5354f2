// shadow_map.hpp - ShadowMap: the depth a light sees, and the filtered lookup of how much of its light reaches a point.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "facet/shaders/brdf.hpp"
#include "facet/simd.hpp"

namespace facet {

// The window depth of the nearest surface along each texel's ray from the light (a directional light's parallel
// rays or a spot's cone), top row first, as facet's framebuffer holds depth.
class ShadowMap {
 public:
  ShadowMap() = default;
  // clip_from_world: the light's view and projection; normal_offset: how far along the surface normal, in world
  // units, a lookup moves first (about a texel and a half), so a lit surface does not shadow itself.
  // depth: size x size values, top row first.
  ShadowMap(const glm::mat4& clip_from_world, int size, std::span<const float> depth, float normal_offset)
      : clip_from_world_(clip_from_world),
        size_(size),
        stride_(size + 2 * kBorder),
        // One more texel past the last row's border: a row of the tent is read as four texels (texel_row).
        depth_(static_cast<std::size_t>(stride_) * static_cast<std::size_t>(stride_) + 1,
               std::numeric_limits<float>::infinity()),
        normal_offset_(normal_offset) {
    for (int y = 0; y < size; ++y)
      std::copy_n(depth.begin() + static_cast<std::ptrdiff_t>(y) * size, size,
                  depth_.begin() + static_cast<std::ptrdiff_t>(y + kBorder) * stride_ + kBorder);
  }

  int size() const { return size_; }

  // The share of the light that reaches `world` on a surface of unit normal n, 0 to 1, for one pixel (F = float,
  // V3 = glm::vec3) or 16 lanes (simd::FloatT, simd::Vec3T), the same operations in the same order for both:
  // percentage-closer filtering over 3 x 3 texels with tent weights (the mean of four bilinear comparisons half a
  // texel apart), so the edge of a shadow is about two texels wide. Points outside the light's view are lit.
  template <class F, class V3>
  FACET_LANES_INLINE F visibility(const V3& world, const V3& n) const {
    using brdf::constant;
    const V3 p = world + n * constant<F>(normal_offset_);
    const glm::mat4& m = clip_from_world_;
    const auto row = [&](int r) { return (m[0][r] * p.x + m[1][r] * p.y) + (m[2][r] * p.z + m[3][r]); };
    const F w = row(3);
    const F inverse_w = constant<F>(1.0f) / w;
    const F x = row(0) * inverse_w, y = row(1) * inverse_w, z = row(2) * inverse_w;
    const float size = static_cast<float>(size_);
    // Texel coordinates of the tent's corner texel and the weights' fractions.
    const F u = (x * 0.5f + 0.5f) * size - 1.0f, v = (0.5f - y * 0.5f) * size - 1.0f;
    const F depth = z * 0.5f + (0.5f - kDepthBias);
    // Inside where in front of the light, before the far plane and near the map (which keeps the indices in range
    // of int): where this maximum is negative (x - x and y - y make it NaN where x or y is). One comparison of a
    // value, since GCC 12 lowers masks combined with | to 16 scalar operations each.
    const F inside = brdf::max(brdf::max(F(-w), F(z - 1.0f)), brdf::max(F(brdf::abs(x) - 1.5f), F(brdf::abs(y) - 1.5f))) +
                     ((x - x) + (y - y));
    const F u0 = brdf::floor(brdf::select(inside < 0.0f, u, constant<F>(0.0f)));
    const F v0 = brdf::floor(brdf::select(inside < 0.0f, v, constant<F>(0.0f)));
    const F fu = u - u0, fv = v - v0;
    const F wu[3] = {(1.0f - fu) * 0.5f, constant<F>(0.5f), fu * 0.5f};
    const F wv[3] = {(1.0f - fv) * 0.5f, constant<F>(0.5f), fv * 0.5f};
    F lit = constant<F>(0.0f);
    for (int j = 0; j < 3; ++j) {
      const std::array<F, 4> stored = texel_row(u0, v0, j);
      F row_lit = constant<F>(0.0f);
      for (int i = 0; i < 3; ++i)
        row_lit = row_lit + brdf::select(depth <= stored[static_cast<std::size_t>(i)], wu[i], constant<F>(0.0f));
      lit = lit + row_lit * wv[j];
    }
    return brdf::select(inside < 0.0f, lit, constant<F>(1.0f));
  }

 private:
  // A constant offset in window depth for the rounding of depth values and the slope within a texel that the
  // normal offset leaves.
  static constexpr float kDepthBias = 2e-4f;

  // The map is stored with a border of kBorder texels of +infinity (never shadowing) on every side, and the
  // tent's corner clamped to [-kBorder, size]: a lookup anywhere reads stored texels without a bounds test, and
  // one off the map reads the border alone.
  static constexpr int kBorder = 3;

  // The stored depths of texels (u0, v0 + j) to (u0 + 3, v0 + j), per pixel or per lane: the tent's row j and
  // one texel more, which the lanes read with the row as one record.
  std::array<float, 4> texel_row(float u0, float v0, int j) const {
    const int x = std::clamp(static_cast<int>(u0), -kBorder, size_) + kBorder;
    const int y = std::clamp(static_cast<int>(v0), -kBorder, size_) + kBorder + j;
    const float* row = depth_.data() + static_cast<std::size_t>(y * stride_ + x);
    return {row[0], row[1], row[2], row[3]};
  }
  template <class L>
  FACET_LANES_INLINE std::array<simd::FloatT<L>, 4> texel_row(const simd::FloatT<L>& u0, const simd::FloatT<L>& v0,
                                                             int j) const {
    using Int = simd::IntT<L>;
    const auto clamp = [this](Int t) {
      t = simd::blend(t < -kBorder, simd::splat<L>(-kBorder), t);
      return simd::blend(t > size_, simd::splat<L>(size_), t);
    };
    const Int index = (clamp(simd::truncate(v0)) + (kBorder + j)) * stride_ + (clamp(simd::truncate(u0)) + kBorder);
    return simd::gather_records<4>(depth_.data(), index);
  }

  glm::mat4 clip_from_world_{1.0f};
  int size_ = 0, stride_ = 0;
  std::vector<float> depth_;
  float normal_offset_ = 0.0f;
};

}  // namespace facet
