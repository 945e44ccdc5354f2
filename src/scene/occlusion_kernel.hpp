// occlusion_kernel.hpp - screen-space ambient occlusion's sampling, for one pixel or for 16 pixels of a row.
#pragma once

#include <cmath>
#include <cstddef>
#include <limits>
#include <numbers>
#include <span>
#include <type_traits>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "facet/shaders/brdf.hpp"
#include "facet/simd.hpp"

namespace facet::detail {

// Scalable Ambient Obscurance (McGuire, Mara and Luebke, 2012): each pixel's samples within a world radius of its
// surface, seen from its normal (from the depth's differences), weigh in by how far above its tangent plane they
// lie, falling off towards the radius. One template serves the scalar reference (float, int) and the lanes of any
// layout (simd::FloatT<L>, simd::IntT<L>), with the same operations in the same order, so all give identical results.
namespace occlusion {

inline constexpr int kSamples = 8;  // per pixel, on a spiral; the 4 x 4 pattern of rotations and the blur make it 128
inline constexpr int kTurns = 3;    // of the spiral, coprime with kSamples so the samples' angles do not repeat
inline constexpr float kMaxRadiusPixels = 48.0f;  // keeps a close-up's reads near their pixel, in cache
inline constexpr int kPad = 64;      // zero depths around the grid, beyond the farthest sample: reads need no bounds
inline constexpr float kBias = 0.002f;  // of the depth: a flat surface's own samples do not occlude it

// The spiral's offsets for each of the 16 rotations of the 4 x 4 pattern, in units of the screen radius: sample i
// at distance (i + 0.5) / N, angle (i + 0.5) / N turns x kTurns plus the pixel's rotation. `lanes` holds the same
// values for 16 pixels of a row starting at a multiple of 4, per row of the pattern.
struct Spiral {
  glm::vec2 offset[16][kSamples];
  alignas(simd::kLaneAlign) float lanes_x[4][kSamples][simd::kLanes];
  alignas(simd::kLaneAlign) float lanes_y[4][kSamples][simd::kLanes];
  Spiral() {
    // A 4 x 4 ordered-dither order, so neighbouring pixels take well-separated rotations and the blur averages them.
    constexpr int kOrder[16] = {0, 8, 2, 10, 12, 4, 14, 6, 3, 11, 1, 9, 15, 7, 13, 5};
    for (int p = 0; p < 16; ++p)
      for (int i = 0; i < kSamples; ++i) {
        const float alpha = (static_cast<float>(i) + 0.5f) / kSamples;
        const float angle = 2.0f * std::numbers::pi_v<float> *
                            (alpha * kTurns + static_cast<float>(kOrder[p]) / 16.0f);
        offset[p][i] = alpha * glm::vec2(std::cos(angle), std::sin(angle));
      }
    for (int row = 0; row < 4; ++row)
      for (int i = 0; i < kSamples; ++i)
        for (int k = 0; k < simd::kLanes; ++k) {
          lanes_x[row][i][k] = offset[(k & 3) + 4 * row][i].x;
          lanes_y[row][i][k] = offset[(k & 3) + 4 * row][i].y;
        }
  }
  // Sample i's offset for the pixel at (x, y); for lanes, x is 16 pixels starting at a multiple of 4.
  glm::vec2 at(int x, int y, int i) const { return offset[(x & 3) + 4 * (y & 3)][i]; }
  template <class L>
  FACET_LANES_INLINE simd::Vec2T<L> at(const simd::IntT<L>&, int y, int i) const {
    return {simd::load<simd::FloatT<L>>(lanes_x[y & 3][i]), simd::load<simd::FloatT<L>>(lanes_y[y & 3][i])};
  }
};

// A width x height plane of floats with kPad zeros on every side, so that reads around a pixel need no bounds: the
// view-space depth of every pixel (0 where nothing was drawn), or the raw openness.
struct Grid {
  int width = 0, height = 0;
  std::size_t stride = 0;
  std::vector<float> values;
  void resize(int w, int h) {
    width = w, height = h;
    stride = static_cast<std::size_t>(w) + 2 * kPad;
    values.assign(stride * (static_cast<std::size_t>(h) + 2 * kPad), 0.0f);
  }
  float* row(int y) { return values.data() + (static_cast<std::size_t>(y) + kPad) * stride + kPad; }
  const float* row(int y) const { return values.data() + (static_cast<std::size_t>(y) + kPad) * stride + kPad; }
};

// A pixel's scalar types, or the lanes' of F's layout.
template <class F>
struct TypesOf {
  using Int = simd::IntT<typename F::layout>;
  using Vec3 = simd::Vec3T<typename F::layout>;
};
template <>
struct TypesOf<float> {
  using Int = int;
  using Vec3 = glm::vec3;
};
template <class F>
using IntOf = typename TypesOf<F>::Int;
template <class F>
using Vec3Of = typename TypesOf<F>::Vec3;

inline float to_float(int v) { return static_cast<float>(v); }
using simd::to_float;
inline int truncate(float v) { return static_cast<int>(v); }
using simd::truncate;
inline float dot(const glm::vec3& a, const glm::vec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
using simd::dot;
template <class F>
FACET_LANES_INLINE Vec3Of<F> cross3(const Vec3Of<F>& a, const Vec3Of<F>& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
// Conditions below are single comparisons of values, tested inside each select: GCC 12 lowers two comparisons'
// masks combined (by & or |, or by nested selects it merges) to 16 scalar operations each. Drawn pixels have a
// negative view-space z, so "drawn and x" is one comparison of a maximum with 0.

// a where l < r, else b, per component.
template <class F>
FACET_LANES_INLINE Vec3Of<F> pick_less(const F& l, const F& r, const Vec3Of<F>& a, const Vec3Of<F>& b) {
  return {brdf::select(l < r, a.x, b.x), brdf::select(l < r, a.y, b.y), brdf::select(l < r, a.z, b.z)};
}

// The pixel x0, or the 16 pixels from x0 on.
template <class F>
FACET_LANES_INLINE IntOf<F> pixels(int x0) {
  if constexpr (std::is_same_v<F, float>) {
    return x0;
  } else {
    return x0 + simd::kLaneIndexT<typename F::layout>;
  }
}
// The value at x0 of a row, or the 16 from x0 on.
template <class F>
FACET_LANES_INLINE F load_at(const float* row, int x0) {
  if constexpr (std::is_same_v<F, float>) {
    return row[x0];
  } else {
    return simd::load<F>(row + x0);
  }
}
// The values at row-relative offsets, per pixel or gathered per lane.
inline float at(const float* row, int x) { return row[x]; }
template <class L>
FACET_LANES_INLINE simd::FloatT<L> at(const float* row, const simd::IntT<L>& x) {
  return simd::gather(row, x);
}

// Where the grids lie in the target the depth was drawn into: its size, and the place of the grids' first pixel.
// The region is a multiple of 16 pixels across and 4 down from the target's corner, so that its strips and the
// spiral's 4 x 4 pattern fall on the same pixels as the whole target's would.
struct Window {
  int width, height;
  int x0 = 0, y0 = 0;
};

// View-space positions rebuilt from a projection's depth: z from the window depth, x and y from the pixel's
// normalized device coordinates (any projection without shear: perspective, orthographic, off-centre). Pixels are
// counted from the window's region.
struct Unprojection {
  glm::mat4 p;
  Window window;
  float inverse_x = 1.0f / p[0][0], inverse_y = 1.0f / p[1][1];

  // View-space z of window depth d (negative in front of the eye), or 0 where nothing was drawn (d = 1).
  template <class F>
  FACET_LANES_INLINE F z(const F& d) const {
    const F ndc = 2.0f * d - 1.0f;
    return brdf::select(d < 1.0f, F((p[3][2] - ndc * p[3][3]) / (ndc * p[2][3] - p[2][2])), brdf::constant<F>(0.0f));
  }
  // For a pixel, or lanes: x and y as ints or lanes of ints, z as float or lanes.
  template <class F, class Y>
  FACET_LANES_INLINE Vec3Of<F> position(const IntOf<F>& x, const Y& y, const F& z) const {
    const F ndc_x = 2.0f * (to_float(x + window.x0) + 0.5f) / static_cast<float>(window.width) - 1.0f;
    const auto ndc_y = 1.0f - 2.0f * (to_float(y + window.y0) + 0.5f) / static_cast<float>(window.height);
    const F w = p[2][3] * z + p[3][3];
    return {(ndc_x * w - p[2][0] * z - p[3][0]) * inverse_x, (ndc_y * w - p[2][1] * z - p[3][1]) * inverse_y, z};
  }
};

// What every pixel's sampling shares.
struct Sampling {
  const Grid& grid;  // view-space depths
  Unprojection unproject;
  float radius;
  float scale;     // pixels per world unit at unit clip w
  float strength;  // the sum's weight: 5 / (samples r^6)
  const Spiral& spiral;

  // The grid covers the region of `window` from its origin on.
  Sampling(const Grid& g, const glm::mat4& clip_from_view, float world_radius, const Spiral& s, const Window& window)
      : grid(g),
        unproject{clip_from_view, window},
        radius(world_radius),
        scale(0.5f * static_cast<float>(window.height) * std::abs(clip_from_view[1][1])),
        strength(5.0f / (kSamples * radius * radius * radius * radius * radius * radius)),
        spiral(s) {}

  // The difference along one axis from surface point p (depth z) towards the nearer of its neighbours a and b
  // (depths za, zb; across an edge the other one lies on another surface); none where neither was drawn.
  template <class F>
  FACET_LANES_INLINE static Vec3Of<F> difference(const F& z, const Vec3Of<F>& p, const F& za, const Vec3Of<F>& a,
                                                 const F& zb, const Vec3Of<F>& b) {
    using V3 = Vec3Of<F>;
    const F zero = brdf::constant<F>(0.0f), far = brdf::constant<F>(std::numeric_limits<float>::infinity());
    // Each neighbour's depth difference, infinite where it was not drawn.
    const F da = brdf::select(za < 0.0f, brdf::abs(F(z - za)), far);
    const F db = brdf::select(zb < 0.0f, brdf::abs(F(zb - z)), far);
    return pick_less<F>(da, db, V3(p - a), pick_less<F>(db, far, V3(b - p), V3{zero, zero, zero}));
  }

  // The raw openness (1 open, 0 occluded) of pixel x0 of row y, or of the 16 pixels from x0 (a multiple of 4) on.
  template <class F>
  FACET_LANES_INLINE F openness(int x0, int y) const {
    using brdf::select;
    using I = IntOf<F>;
    using V3 = Vec3Of<F>;
    const I x = pixels<F>(x0);
    const float* row = grid.row(y);
    const int stride = static_cast<int>(grid.stride);
    const F zero = brdf::constant<F>(0.0f), one = brdf::constant<F>(1.0f);
    const F z = load_at<F>(row, x0);
    const V3 p = unproject.position<F>(x, y, z);
    const F za_x = load_at<F>(row, x0 - 1), zb_x = load_at<F>(row, x0 + 1);
    const F za_y = load_at<F>(row - stride, x0), zb_y = load_at<F>(row + stride, x0);
    const V3 dx = difference<F>(z, p, za_x, unproject.position<F>(I(x - 1), y, za_x), zb_x,
                                unproject.position<F>(I(x + 1), y, zb_x));
    const V3 dy = difference<F>(z, p, za_y, unproject.position<F>(x, y - 1, za_y), zb_y,
                                unproject.position<F>(x, y + 1, zb_y));
    V3 n = cross3<F>(dx, dy);
    const F length = brdf::sqrt(F(dot(n, n)));
    // Shaded where drawn (z < 0) with a normal (length > 0).
    const F shaded = brdf::max(z, F(-length));
    const F divisor = select(shaded < 0.0f, length, one);
    n = V3{n.x / divisor, n.y / divisor, n.z / divisor};
    n = pick_less<F>(zero, F(dot(n, p)), V3{-n.x, -n.y, -n.z}, n);  // towards the eye
    const F screen_radius =
        brdf::min(F(radius * scale / (unproject.p[2][3] * z + unproject.p[3][3])), brdf::constant<F>(kMaxRadiusPixels));
    // Sampled where shaded and the radius spans more than a pixel.
    const F sampled = brdf::max(shaded, F(1.0f - screen_radius));
    // Unsampled pixels read their own depth, inside the grid whatever their radius.
    const F reach = select(sampled < 0.0f, screen_radius, zero);
    const float r2 = radius * radius;
    F sum = zero;
    for (int i = 0; i < kSamples; ++i) {
      const auto offset = spiral.at(x, y, i);
      // Rounded to the nearest pixel (the offsets are at most kMaxRadiusPixels: the shift keeps them positive).
      const I sx = truncate(F(offset.x * reach + 64.5f)) - 64;
      const I sy = truncate(F(offset.y * reach + 64.5f)) - 64;
      const F sz = at(row, I(x + sx - sy * stride));
      const V3 v = unproject.position<F>(I(x + sx), I(y - sy), sz) - p;
      const F vv = dot(v, v), vn = dot(v, n);
      const F falloff = brdf::max(F(r2 - vv), zero);
      const F term = falloff * falloff * falloff * brdf::max(F((vn + kBias * z) / (vv + 0.01f * r2)), zero);
      sum = sum + select(sz != 0.0f, term, zero);
    }
    return select(sampled < 0.0f, brdf::max(F(1.0f - sum * strength), zero), one);
  }

  // The mean raw openness over the 4 x 4 pixels around (x, y) whose depth lies within 5% of this pixel's, which
  // removes the rotation pattern's noise without blurring across edges; 1 where nothing was drawn.
  template <class F>
  FACET_LANES_INLINE F blurred(const Grid& raw, int x0, int y) const {
    const F z = load_at<F>(grid.row(y), x0);
    const F zero = brdf::constant<F>(0.0f), one = brdf::constant<F>(1.0f);
    F sum = zero, count = zero;
    for (int sy = y - 1; sy <= y + 2; ++sy) {
      const float* zs = grid.row(sy);
      const float* open = raw.row(sy);
      for (int dx = -1; dx <= 2; ++dx) {
        const F s = load_at<F>(zs, x0 + dx);
        // Drawn (s < 0) and within 5% of z.
        const F similar = brdf::max(s, F(brdf::abs(F(s - z)) + 0.05f * z));
        sum = sum + brdf::select(similar < 0.0f, load_at<F>(open, x0 + dx), zero);
        count = count + brdf::select(similar < 0.0f, one, zero);
      }
    }
    return brdf::select(z < 0.0f, F(sum / brdf::select(z < 0.0f, count, one)), one);
  }
};

// The part of a w x h target the grids cover: the target and the region's place in it, and its size.
struct Region {
  Window window;
  int width, height;
};
// A box of an object (its corners, object space) and the matrix that takes them to clip space.
struct ClipBox {
  glm::mat4 clip_from_object;
  glm::vec3 min, max;
};
// The region of a w x h target within which a depth pass of the boxes' contents can draw: the pixels within the
// screen rectangle of every box's corners, widened by a pixel for rounding, its origin moved to a multiple of 16
// across and 4 down (Window); the whole target if a corner lies behind the eye, a strip of background without boxes.
// A model that fills a fifth of the frame leaves the occlusion's passes four fifths less to sweep, with the same
// values inside, since every read beyond the region finds nothing drawn there, as it would in the target. Defined
// in ambient_occlusion.cpp.
Region region_of(std::span<const ClipBox> boxes, int w, int h);

// The stages of a frame's occlusion for row y, 16 lanes at a time, with the values the templates above give pixel
// by pixel: the view-space depths from the window depths of the row (`depth`, width values) into the sampling's
// grid; the raw openness into `raw`; the blurred openness into `open` (width values). Defined in
// ambient_occlusion.cpp.
void depth_row(const Unprojection& unproject, const float* depth, int width, float* z);
void openness_row(const Sampling& sampling, int y, Grid& raw);
void blurred_row(const Sampling& sampling, const Grid& raw, int y, float* open);

}  // namespace occlusion
}  // namespace facet::detail
