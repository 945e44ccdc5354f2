// multisample.hpp - sample positions, and a set-up triangle's edges and depth seen from one sample of every pixel.
#pragma once

#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstdint>

#include "facet/detail/binning.hpp"
#include "facet/detail/triangle_setup.hpp"
#include "facet/framebuffer.hpp"

namespace facet::detail {

// A sample's place in its pixel, in 1/256 pixel from the pixel's centre, y down.
struct SampleOffset {
  std::int32_t x, y;
};

// The standard sample locations of Vulkan (the same as Direct3D's), given there in 1/16 pixel from the pixel's
// top-left corner; sample 0 comes first.
struct SamplePattern {
  int count;
  SampleOffset offset[kMaxSamples];
  int lo, hi;  // the range of positions from the pixel's top-left corner, both ways, in 1/256 pixel
};

constexpr SamplePattern make_sample_pattern(int count, const int (&sixteenths)[kMaxSamples][2]) {
  SamplePattern p{count, {}, kSubpixelScale, 0};
  for (int s = 0; s < count; ++s) {
    const int x = sixteenths[s][0] * 16, y = sixteenths[s][1] * 16;
    p.offset[s] = {x - kSubpixelScale / 2, y - kSubpixelScale / 2};
    p.lo = std::min({p.lo, x, y});
    p.hi = std::max({p.hi, x, y});
  }
  return p;
}

inline constexpr SamplePattern kSamplePatterns[4] = {
    make_sample_pattern(1, {{8, 8}}),
    make_sample_pattern(2, {{12, 12}, {4, 4}}),
    make_sample_pattern(4, {{6, 2}, {14, 6}, {2, 10}, {10, 14}}),
    make_sample_pattern(8, {{9, 5}, {7, 11}, {13, 9}, {5, 3}, {3, 13}, {1, 7}, {11, 15}, {15, 1}}),
};

// The pattern of 1, 2, 4 or 8 samples (what Framebuffer accepts).
inline const SamplePattern& sample_pattern(int samples) {
  return kSamplePatterns[samples >= 8 ? 3 : (samples >= 4 ? 2 : (samples >= 2 ? 1 : 0))];
}

// The triangle as the rasterizer sees it from sample `sample` of each pixel: coverage of pixel (i, j) by the
// result is the coverage of that sample of (i, j) by the triangle, exactly (the same integers as the centre's,
// with the fill rule), and its depth plane evaluated at a pixel centre gives the depth at that sample. Its
// interpolation planes are shifted alike; the fragment shader still runs at the pixel centre, with the triangle
// itself. Its bounds hold the pixels whose sample lies within the snapped corners' extremes: the triangle's own
// bounds hold those of any sample, and a small triangle's bounds are often a pixel wider than each sample's.
inline TriangleSetup at_sample(const TriangleSetup& tri, const SamplePattern& pattern, int sample) {
  const SampleOffset o = pattern.offset[sample];
  TriangleSetup view = tri;
  for (int e = 0; e < 3; ++e) {
    const Edge& edge = tri.edge[e];
    // k at the sample: k at the centre, which q and the fraction hold, plus the edge's gradient times the offset.
    const std::int64_t k =
        edge.q * kSubpixelScale + tri.edge_fraction[e] + std::int64_t{edge.a} * o.x + std::int64_t{edge.b} * o.y;
    view.edge[e].q = k >> kSubpixelBits;
  }
  // A corner extreme m (a multiple of 256 plus its fraction f) admits pixel p when p * 256 + position lies on the
  // inside of it: the first pixel is one further on for a sample at a position below f than for one at or above,
  // and the bounds were drawn for the farthest position of the pattern.
  const int x = o.x + kSubpixelScale / 2, y = o.y + kSubpixelScale / 2;
  const auto below = [](int fraction, int position) { return fraction > position ? 1 : 0; };
  const auto f = [&](int k) { return static_cast<int>((tri.bounds_fraction >> (8 * k)) & 0xffu); };
  view.min_x = static_cast<std::int16_t>(tri.min_x + below(f(0), x) - below(f(0), pattern.hi));
  view.min_y = static_cast<std::int16_t>(tri.min_y + below(f(1), y) - below(f(1), pattern.hi));
  view.max_x = static_cast<std::int16_t>(tri.max_x - below(x, f(2)) + below(pattern.lo, f(2)));
  view.max_y = static_cast<std::int16_t>(tri.max_y - below(y, f(3)) + below(pattern.lo, f(3)));
  // Planes are evaluated at (pixel centre - origin): moving the origin back by the offset moves that to the sample.
  view.origin_x = tri.origin_x - static_cast<float>(o.x) / kSubpixelScale;
  view.origin_y = tri.origin_y - static_cast<float>(o.y) / kSubpixelScale;
  return view;
}

// One row of a tile's resolve (Framebuffer::store_tile) with the sample count a constant: the loop over samples
// unrolls, and the loop over the row's pixels vectorises (one contiguous load per sample plane), where a run-time
// count kept it scalar.
template <int kSamples>
[[gnu::always_inline]] inline void resolve_row(const std::uint32_t* in, std::size_t sample_stride, std::uint32_t* out,
                                               int width) {
  constexpr int kShift = std::countr_zero(static_cast<unsigned>(kSamples));
  constexpr std::uint32_t kRound = 0x00010001u * static_cast<std::uint32_t>(kSamples / 2);
  for (int x = 0; x < width; ++x) {
    std::uint32_t even = kRound, odd = kRound;  // bytes 0 and 2 (red, blue), bytes 1 and 3 (green, alpha)
    for (int s = 0; s < kSamples; ++s) {
      const std::uint32_t c = in[sample_stride * static_cast<std::size_t>(s) + static_cast<std::size_t>(x)];
      even += c & 0x00ff00ffu;
      odd += (c >> 8) & 0x00ff00ffu;
    }
    out[x] = ((even >> kShift) & 0x00ff00ffu) | ((odd >> kShift) & 0x00ff00ffu) << 8;
  }
}

// The tile work of sample s: its colour and depth planes, depth bounds and the thread's scratch for it.
inline TileWork sample_work(const TileWork& work, int s) {
  TileWork one = work;
  one.color += work.sample_stride * static_cast<std::size_t>(s);
  one.depth += work.sample_stride * static_cast<std::size_t>(s);
  one.depth_bounds += work.bounds_stride * static_cast<std::size_t>(s);
  one.scratch += s;
  return one;
}

}  // namespace facet::detail
