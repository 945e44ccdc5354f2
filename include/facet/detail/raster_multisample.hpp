// raster_multisample.hpp - rasterization of one tile with several samples per pixel, immediate and deferred.
#pragma once

#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>

#include "facet/detail/multisample.hpp"
#include "facet/detail/raster.hpp"
#include "facet/detail/raster_deferred.hpp"

namespace facet::detail {

// Multisampling as OpenGL does it: coverage, the fill rule and the depth test per sample, each sample seeing the
// triangle through at_sample; the fragment shader once per pixel and triangle, at the pixel centre (extrapolated
// where the centre itself is outside, as GL does without the centroid qualifier); its colour written to every
// covered sample that passed. Every sample plane keeps its own hierarchical depth bounds.

// Immediate shading of one triangle: per 8x8 block, each sample's hierarchical depth test and coverage, then the
// quads any sample covers.
template <Shader S>
[[gnu::always_inline]] inline void raster_triangle_multisample(const ShadeContext<S>& ctx, const TriangleSetup& tri,
                                                               const TileWork& work) {
  const RenderState& state = *ctx.state;
  const int n = work.samples;
  const SamplePattern& pattern = sample_pattern(n);
  TriangleSetup views[kMaxSamples];
  for (int s = 0; s < n; ++s) views[s] = at_sample(tri, pattern, s);

  const int x0 = std::max<int>(tri.min_x, work.x0), x1 = std::min<int>(tri.max_x, work.x1 - 1);
  const int y0 = std::max<int>(tri.min_y, work.y0), y1 = std::min<int>(tri.max_y, work.y1 - 1);
  if (x0 > x1 || y0 > y1) return;
  const bool less = state.depth_func == DepthFunc::less, lequal = state.depth_func == DepthFunc::lequal;
  // As raster_blocks: LESS and LEQUAL writes only lower depth, other functions' writes make bounds follow them up.
  const bool reject_hidden = state.depth_test && (less || lequal);
  const bool writes_depth = state.depth_test && state.depth_write;
  for (int by = y0 & ~(kBlockSize - 1); by <= y1; by += kBlockSize) {
    for (int bx = x0 & ~(kBlockSize - 1); bx <= x1; bx += kBlockSize) {
      const int i0 = std::max(x0 - bx, 0), i1 = std::min(x1 - bx, kBlockSize - 1);
      const int j0 = std::max(y0 - by, 0), j1 = std::min(y1 - by, kBlockSize - 1);
      const std::size_t block = static_cast<std::size_t>((by - work.y0) / kBlockSize * (kTileSize / kBlockSize) +
                                                         (bx - work.x0) / kBlockSize);
      const auto range = [&](int s) __attribute__((always_inline)) {
        return raster_block_depth_range(views[s], state.depth_offset, bx + i0, by + j0, bx + i1, by + j1);
      };
      std::uint64_t mask[kMaxSamples], any = 0;
      for (int s = 0; s < n; ++s) {
        mask[s] = 0;
        const float bound = work.depth_bounds[work.bounds_stride * static_cast<std::size_t>(s) + block];
        if (reject_hidden && bound < 1.0f) {
          const float nearest = range(s).nearest;
          if (less ? nearest - kDepthBoundMargin >= bound : nearest - kDepthBoundMargin > bound) continue;
        }
        // Within the sample's own bounds: a rectangle's edges (a point's square) pass everywhere, and only those
        // bounds shape it, which may be a pixel narrower than the bounds over all samples.
        const TriangleSetup& view = views[s];
        const int si0 = std::max(i0, view.min_x - bx), si1 = std::min(i1, view.max_x - bx);
        const int sj0 = std::max(j0, view.min_y - by), sj1 = std::min(j1, view.max_y - by);
        if (si0 > si1 || sj0 > sj1) continue;
        mask[s] = raster_block_coverage(view, bx, by, si0, si1, sj0, sj1);
        any |= mask[s];
      }
      if (!any) continue;
      for (int qy = 0; qy < kBlockSize; qy += 2)
        for (int qx = 0; qx < kBlockSize; qx += 2) {
          unsigned bits[4] = {0, 0, 0, 0};
          for (int k = 0; k < 4; ++k) {
            const int bit = (qy + (k >> 1)) * kBlockSize + qx + (k & 1);
            if (!((any >> bit) & 1)) continue;
            for (int s = 0; s < n; ++s) bits[k] |= static_cast<unsigned>((mask[s] >> bit) & 1) << s;
          }
          if (bits[0] | bits[1] | bits[2] | bits[3])
            shade_quad_samples<S, true>(ctx, tri, views, work, bx + qx, by + qy, bits);
        }
      if (!writes_depth) continue;
      for (int s = 0; s < n; ++s) {
        // A discarding shader may leave covered samples unwritten: its blocks never count as full.
        const bool full = mask[s] == ~std::uint64_t{0} && !ShaderTraits<S>::may_discard;
        if (!(full || (!reject_hidden && mask[s]))) continue;
        float& bound = work.depth_bounds[work.bounds_stride * static_cast<std::size_t>(s) + block];
        const float farthest = std::min(range(s).farthest + kDepthBoundMargin, 1.0f);
        bound = reject_hidden ? std::min(bound, farthest) : std::max(bound, farthest);
      }
    }
  }
}

// Deferred shading with several samples: the visibility pass of every sample plane, triangle by triangle in draw
// order, then one shading pass over the strips. The shader runs at the pixel centre, so all samples of a pixel that
// kept one triangle take one colour: a lane shader shades the strip in rounds, each giving every lane the triangle
// of its first sample still waiting; other shaders shade the samples in order, each copying the colours of an
// earlier sample's triangles and shading only the triangles new to the pixel. Inside a triangle that is one shading
// per pixel; on an edge, one per triangle meeting there.
// L: the lane layout of this CPU level's copy (detail/dispatch.hpp).
template <Shader S, class L>
[[gnu::always_inline]] inline void raster_tile_deferred_multisample(const ShadeContext<S>& ctx, const TileWork& work,
                                                                    L) {
  const RenderState& state = *ctx.state;
  const int n = work.samples;
  TileWork planes[kMaxSamples];
  settle_clear(work, true, false);  // strips store the samples they cover; the clear depth goes to the scratch
  for (int s = 0; s < n; ++s) {
    planes[s] = sample_work(work, s);
    begin_tile_scratch(planes[s], state.depth_test);
  }

  raster_tile_visibility_multisample(state, work, planes);

  RenderState resolved = state;
  resolved.depth_test = false;
  const ShadeContext<S> shade{ctx.shader, &resolved};
  const int width = work.x1 - work.x0, height = work.y1 - work.y0;
  // Per strip, each sample's 16 colours. Lanes a sample does not cover keep an older strip's values, which nothing
  // reads.
  alignas(64) std::uint32_t colors[kMaxSamples][simd::kLanes] = {};
  for (int block_y = 0; block_y * kScratchBlock < height; ++block_y)
    for (int block_x = 0; block_x * kScratchBlock < width; ++block_x)
      for (int strip = 0; strip < kScratchBlock / 2; ++strip) {
        const std::size_t at = scratch_index(block_x, block_y) + static_cast<std::size_t>(strip) * simd::kLanes;
        const int px = work.x0 + block_x * kScratchBlock, py = work.y0 + block_y * kScratchBlock + 2 * strip;
        const std::uint32_t* refs[kMaxSamples];
        unsigned covered[kMaxSamples];
        [[maybe_unused]] unsigned pending[kMaxSamples];  // lanes not yet shaded, for lane shaders
        [[maybe_unused]] unsigned waiting = 0;
        for (int s = 0; s < n; ++s) {
          refs[s] = planes[s].scratch->triangle + at;
          covered[s] = pending[s] = ~strip_lanes_equal<L>(refs[s], kNoTriangle) & 0xffffu;
          waiting |= covered[s];
        }
        if constexpr (ShaderTraits<S>::fragment_lanes) {
          // Each (pixel, triangle) pair of the strip is shaded once, whichever samples it covers: a round shades,
          // in every lane, the triangle of the first sample still waiting there, and gives the colour to each
          // sample holding that triangle in that lane. Inside a triangle that is one round; where edges cross the
          // strip, one more for each further triangle a pixel meets.
          // This CPU level's lane types: the default ones are one 512-bit vector, which copies without AVX-512
          // hold in memory and work on lane by lane (a 4-sample frame's shading rounds took 3.5 times as long
          // with AVX2 as with AVX-512).
          FACET_LANE_TYPES(L);
          const auto lanes_of = [](unsigned bits) __attribute__((always_inline)) {
            return (((Int{} + static_cast<std::int32_t>(bits)) >> simd::kLaneIndexT<L>) & 1) != 0;
          };
          // Inside triangles, every sample of every pixel holds the same triangle: one round, and every sample
          // plane takes the same colours, without sorting them out sample by sample.
          UInt differ = UInt{};
          for (int s = 1; s < n; ++s) differ |= simd::load<UInt>(refs[s]) ^ simd::load<UInt>(refs[0]);
          if (simd::lane_bits(differ != 0u) == 0) {
            if (covered[0]) {
              FragmentLanes<typename S::Varyings, L> fragment;
              prepare_strip_lanes(shade, planes[0], px, py, refs[0], nullptr, fragment);
              alignas(64) std::uint32_t strip_colors[simd::kLanes];
              shade_lanes(*ctx.shader, fragment, strip_colors);
              for (int s = 0; s < n; ++s) store_strip(planes[s], px, py, covered[0], strip_colors);
            }
            continue;
          }
          while (waiting) {
            UInt own_refs = UInt{} + kNoTriangle;
            for (int s = n - 1; s >= 0; --s)
              own_refs = simd::blend(lanes_of(pending[s]), simd::load<UInt>(refs[s]), own_refs);
            alignas(64) std::uint32_t own[simd::kLanes];
            simd::store(own, own_refs);
            FragmentLanes<typename S::Varyings, L> fragment;
            prepare_strip_lanes(shade, planes[0], px, py, own, nullptr, fragment);
            alignas(64) std::uint32_t own_colors[simd::kLanes];
            shade_lanes(*ctx.shader, fragment, own_colors);
            const UInt shaded = simd::load<UInt>(own_colors);
            waiting = 0;
            for (int s = 0; s < n; ++s) {
              if (!pending[s]) continue;
              const unsigned taken = simd::lane_bits(simd::load<UInt>(refs[s]) == own_refs) & pending[s];
              simd::store(colors[s], simd::blend(lanes_of(taken), shaded, simd::load<UInt>(colors[s])));
              waiting |= pending[s] &= ~taken;
            }
          }
          for (int s = 0; s < n; ++s)
            if (covered[s]) store_strip(planes[s], px, py, covered[s], colors[s]);
        } else {
          for (int s = 0; s < n; ++s) {
            const TileWork& plane = planes[s];
            if (!covered[s]) continue;
            std::uint32_t* out = colors[s];
            // Lanes whose triangle an earlier sample kept take that sample's colour; the rest are shaded.
            unsigned copied = 0;
            for (int t = 0; t < s && (covered[s] & ~copied); ++t) {
              unsigned same = 0;
#pragma GCC unroll 1
              for (int k = 0; k < simd::kLanes; ++k) {
                const bool take = refs[s][k] == refs[t][k] && !((copied >> k) & 1) && ((covered[s] >> k) & 1);
                out[k] = take ? colors[t][k] : out[k];
                same |= static_cast<unsigned>(take) << k;
              }
              copied |= same;
            }
            const unsigned shaded = covered[s] & ~copied;
            for (unsigned pending = shaded; pending;) {
              const std::uint32_t ref = refs[s][std::countr_zero(pending)];
              const unsigned same = strip_lanes_equal<L>(refs[s], ref) & shaded;
              pending &= ~same;
              shade_block_quads(shade, triangle_at(work, ref), plane, px, py, std::uint64_t{same});
            }
            for (unsigned b = shaded; b; b &= b - 1) {
              const int k = std::countr_zero(b);
              out[k] = plane.color[work.at(px + (k & 7), py + (k >> 3))];
            }
            store_strip(plane, px, py, covered[s], out);
          }
        }
      }

  if (state.depth_test && state.depth_write) {
    for (int s = 0; s < n; ++s) store_tile_depth(planes[s]);
    work.lazy_clear->depth = false;
  }
}

}  // namespace facet::detail
