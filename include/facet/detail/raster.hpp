// raster.hpp - rasterization of one tile: block coverage (tile -> 8x8 block -> pixel), 2x2 quad shading, depth.
#pragma once

#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstdint>

#include "facet/detail/binning.hpp"
#include "facet/detail/dispatch.hpp"
#include "facet/detail/triangle_setup.hpp"
#include "facet/framebuffer.hpp"
#include "facet/render_state.hpp"
#include "facet/shader.hpp"

namespace facet::detail {

inline constexpr int kBlockSize = 8;  // one 64-bit coverage mask per block, bit j * 8 + i for pixel (i, j)

template <Shader S>
struct ShadeContext {
  const S* shader;
  const RenderState* state;
};

inline bool depth_passes(DepthFunc func, float fragment, float stored) {
  switch (func) {
    case DepthFunc::never: return false;
    case DepthFunc::less: return fragment < stored;
    case DepthFunc::equal: return fragment == stored;
    case DepthFunc::lequal: return fragment <= stored;
    case DepthFunc::greater: return fragment > stored;
    case DepthFunc::notequal: return fragment != stored;
    case DepthFunc::gequal: return fragment >= stored;
    case DepthFunc::always: return true;
  }
  return false;
}

// The bits of the rectangle [i0, i1] x [j0, j1] of a block, 0 <= i0 <= i1 < 8 and 0 <= j0 <= j1 < 8. Without a
// loop over the rows: a triangle's rectangles have 1 to 8 rows at random, and that loop's exit mispredicts.
inline std::uint64_t block_rect_mask(int i0, int i1, int j0, int j1) {
  const std::uint64_t row = ((std::uint64_t{2} << i1) - 1) & ~((std::uint64_t{1} << i0) - 1);
  const std::uint64_t rows =
      (~std::uint64_t{0} >> (63 - (kBlockSize * j1 + kBlockSize - 1))) & (~std::uint64_t{0} << (kBlockSize * j0));
  return row * 0x0101010101010101u & rows;  // row < 256: the product copies it into every byte, without carries
}

// Pixels (bx + i, by + j), i in [i0, i1], j in [j0, j1] (a rectangle inside one 8x8 block), whose centres are
// inside all three edges. Whole-rectangle accept and reject use 64-bit values; an edge that crosses the rectangle
// is tested per pixel in 32 bits (see Edge). Restricting the work to the triangle's bounds keeps the many tiny
// triangles of dense meshes from paying for whole blocks.
[[gnu::always_inline]] inline std::uint64_t raster_block_coverage(const TriangleSetup& tri, int bx, int by, int i0,
                                                                  int i1, int j0, int j1) {
  std::uint64_t mask = block_rect_mask(i0, i1, j0, j1);
  for (const Edge& e : tri.edge) {
    const std::int64_t at_corner = std::int64_t{e.a} * (bx + i0) + std::int64_t{e.b} * (by + j0) + e.q;
    const std::int64_t step_a = std::int64_t{e.a} * (i1 - i0), step_b = std::int64_t{e.b} * (j1 - j0);
    const std::int64_t lowest = at_corner + std::min<std::int64_t>(0, step_a) + std::min<std::int64_t>(0, step_b);
    const std::int64_t highest = at_corner + std::max<std::int64_t>(0, step_a) + std::max<std::int64_t>(0, step_b);
    if (highest < 0) return 0;
    if (lowest >= 0) continue;
    const std::int32_t base = static_cast<std::int32_t>(at_corner);
    std::uint64_t edge_mask = 0;
    for (int j = j0; j <= j1; ++j) {
      const std::int32_t row = base + (j - j0) * e.b;
      std::uint32_t bits = 0;
      for (int i = i0; i <= i1; ++i) bits |= static_cast<std::uint32_t>(row + (i - i0) * e.a >= 0) << i;
      edge_mask |= std::uint64_t{bits} << (j * kBlockSize);
    }
    mask &= edge_mask;
  }
  return mask;
}

inline std::uint64_t raster_block_coverage(const TriangleSetup& tri, int bx, int by) {
  return raster_block_coverage(tri, bx, by, 0, kBlockSize - 1, 0, kBlockSize - 1);
}

// Shades the covered pixels of the 2x2 quad at (px, py), pixel k at (px + (k & 1), py + (k >> 1)). bits[k] holds
// pixel k's covered samples, sample s in bit s; views[s] is the triangle seen from sample s (at_sample), views[0] the
// triangle itself without multisampling (kMulti false: one sample, at the centre). Depth is tested and written per
// sample; the shader runs once per pixel, at its centre, and its colour goes to every sample that passed.
// Always inlined, like raster_triangle: both must be compiled inside each CPU level's copy of raster_tile.
template <Shader S, bool kMulti>
[[gnu::always_inline]] inline void shade_quad_samples(const ShadeContext<S>& ctx, const TriangleSetup& tri,
                                                      const TriangleSetup* views, const TileWork& work, int px, int py,
                                                      unsigned (&bits)[4]) {
  using Varyings = typename S::Varyings;
  constexpr std::size_t kFloats = float_count_v<Varyings>;
  constexpr bool kDerivatives = ShaderTraits<S>::needs_derivatives;
  constexpr int kMaxN = kMulti ? kMaxSamples : 1;
  const int n = kMulti ? work.samples : 1;
  const RenderState& state = *ctx.state;
  const bool early_depth = !ShaderTraits<S>::may_discard && state.depth_test;

  float z[4][kMaxN];
  std::size_t index[4];
  for (int k = 0; k < 4; ++k) {
    for (int s = 0; s < n; ++s) {
      const float dx = static_cast<float>(px + (k & 1)) + 0.5f - views[s].origin_x;
      const float dy = static_cast<float>(py + (k >> 1)) + 0.5f - views[s].origin_y;
      z[k][s] = std::clamp(evaluate(views[s].depth, dx, dy) + state.depth_offset, 0.0f, 1.0f);
    }
    index[k] = work.at(px + (k & 1), py + (k >> 1));
  }
  // Drops pixel k's samples that fail the depth test, and writes the depth of those that pass.
  const auto test_depth = [&](int k) __attribute__((always_inline)) {
    for (unsigned pending = bits[k]; pending; pending &= pending - 1) {
      const int s = std::countr_zero(pending);
      float& stored = work.depth[work.sample_stride * static_cast<std::size_t>(s) + index[k]];
      if (!depth_passes(state.depth_func, z[k][s], stored)) bits[k] &= ~(1u << s);
      else if (state.depth_write) stored = z[k][s];
    }
  };
  if (early_depth)
    for (int k = 0; k < 4; ++k) test_depth(k);
  unsigned covered = 0;
  for (int k = 0; k < 4; ++k) covered |= static_cast<unsigned>(bits[k] != 0) << k;
  if (!covered) return;

  // Perspective-correct weights of the source vertices: b/w and 1/w are linear in screen space.
  FloatArray<Varyings> value[4];
  [[maybe_unused]] float centre_z[4];
  const float* v0 = work.varyings + std::size_t{tri.vertex[0]} * kFloats;
  const float* v1 = work.varyings + std::size_t{tri.vertex[1]} * kFloats;
  const float* v2 = work.varyings + std::size_t{tri.vertex[2]} * kFloats;
  for (int k = 0; k < 4; ++k) {
    if (!kDerivatives && !(covered & (1u << k))) continue;
    const float dx = static_cast<float>(px + (k & 1)) + 0.5f - tri.origin_x;
    const float dy = static_cast<float>(py + (k >> 1)) + 0.5f - tri.origin_y;
    if constexpr (kMulti) centre_z[k] = std::clamp(evaluate(tri.depth, dx, dy) + state.depth_offset, 0.0f, 1.0f);
    const float w = 1.0f / evaluate(tri.inv_w, dx, dy);
    const float b1 = evaluate(tri.b1_over_w, dx, dy) * w, b2 = evaluate(tri.b2_over_w, dx, dy) * w;
    // Weighted sum of the three vertices' values rather than v0 + b1 (v1 - v0) + b2 (v2 - v0): errors of the same
    // order for weights in [0, 1], and the lane version then multiplies each value straight from memory (broadcast
    // operands) instead of forming its differences first: 5 operations per varying instead of 12 (AVX-512).
    const float b0 = 1.0f - b1 - b2;
    for (std::size_t f = 0; f < kFloats; ++f) value[k][f] = b0 * v0[f] + b1 * v1[f] + b2 * v2[f];
  }

  Fragment<Varyings> fragment;
  fragment.primitive = tri.primitive;
  fragment.front_facing = tri.front_facing;
  if constexpr (kDerivatives) {
    FloatArray<Varyings> ddx, ddy;
    for (std::size_t f = 0; f < kFloats; ++f) {
      ddx[f] = value[1][f] - value[0][f];
      ddy[f] = value[2][f] - value[0][f];
    }
    fragment.ddx = from_floats<Varyings>(ddx);
    fragment.ddy = from_floats<Varyings>(ddy);
  }
  for (int k = 0; k < 4; ++k) {
    if (!(covered & (1u << k))) continue;
    fragment.varyings = from_floats<Varyings>(value[k]);
    fragment.screen = glm::vec3(static_cast<float>(px + (k & 1)) + 0.5f, static_cast<float>(py + (k >> 1)) + 0.5f,
                                kMulti ? centre_z[k] : z[k][0]);
    glm::vec4 color;
    if constexpr (ShaderTraits<S>::may_discard) {
      const auto result = ctx.shader->fragment(fragment);
      if (!result) continue;
      color = *result;
      if (state.depth_test) {
        test_depth(k);
        if (!bits[k]) continue;
      }
    } else {
      color = ctx.shader->fragment(fragment);
    }
    if (!state.color_write) continue;
    for (unsigned pending = bits[k]; pending; pending &= pending - 1) {
      std::uint32_t& out =
          work.color[work.sample_stride * static_cast<std::size_t>(std::countr_zero(pending)) + index[k]];
      glm::vec4 shaded = color;
      if (state.blend == BlendMode::alpha) {
        const float a = std::clamp(color.a, 0.0f, 1.0f);
        const glm::vec4 under = unpack_rgba8(out);
        shaded = glm::vec4(glm::vec3(color) * a + glm::vec3(under) * (1.0f - a), a + under.a * (1.0f - a));
      }
      out = pack_rgba8(shaded);
    }
  }
}

// One sample per pixel, at its centre: `covered` has bit k for pixel k of the quad.
template <Shader S>
[[gnu::always_inline]] inline void shade_quad(const ShadeContext<S>& ctx, const TriangleSetup& tri,
                                              const TileWork& work, int px, int py, unsigned covered) {
  unsigned bits[4] = {covered & 1u, (covered >> 1) & 1u, (covered >> 2) & 1u, (covered >> 3) & 1u};
  shade_quad_samples<S, false>(ctx, tri, &tri, work, px, py, bits);
}

// Hierarchical depth works with an upper bound on the stored depth of each 8x8 block. The plane's extremes over a
// block are at its corner pixels; kDepthBoundMargin covers the float rounding of evaluating the plane elsewhere.
inline constexpr float kDepthBoundMargin = 4e-6f;

struct DepthRange {
  float nearest, farthest;
};

inline DepthRange raster_block_depth_range(const TriangleSetup& tri, float depth_offset, int x0, int y0, int x1,
                                           int y1) {
  const float dx0 = static_cast<float>(x0) + 0.5f - tri.origin_x, dx1 = static_cast<float>(x1) + 0.5f - tri.origin_x;
  const float dy0 = static_cast<float>(y0) + 0.5f - tri.origin_y, dy1 = static_cast<float>(y1) + 0.5f - tri.origin_y;
  // evaluate() rounds (at_origin + ddx * dx) + ddy * dy, which is monotone in dx and in dy, so the signs of the
  // gradients pick the corners where the plane is lowest and highest: the same values as the minimum and maximum
  // over all four corners, for half the evaluations.
  const bool rises_x = tri.depth.ddx >= 0.0f, rises_y = tri.depth.ddy >= 0.0f;
  const float lowest = evaluate(tri.depth, rises_x ? dx0 : dx1, rises_y ? dy0 : dy1);
  const float highest = evaluate(tri.depth, rises_x ? dx1 : dx0, rises_y ? dy1 : dy0);
  return {std::clamp(lowest + depth_offset, 0.0f, 1.0f), std::clamp(highest + depth_offset, 0.0f, 1.0f)};
}

// What a block's pixel pass reports to the block walk: whether it drew any pixel, and whether the triangle covers
// every pixel of the block (then, under LESS or LEQUAL, each stored depth ends at most the plane's farthest, whether
// the triangle passed there or not).
struct BlockCoverage {
  bool any, full;
};

// Walks the 8x8 blocks of the triangle's bounds within the tile: hierarchical depth rejects hidden blocks, then
// cover(bx, by, i0, i1, j0, j1) handles the pixels of the block's rectangle [i0, i1] x [j0, j1] and returns a
// BlockCoverage, and the block's depth bound follows the writes. Shared by immediate shading and the visibility
// pass of deferred shading, which must reject and bound blocks alike. depth_test is the state's (the visibility
// pass passes it as a constant).
template <class Cover>
[[gnu::always_inline]] inline void raster_blocks(const TriangleSetup& tri, const TileWork& work, bool depth_test,
                                                 const RenderState& state, Cover&& cover) {
  const int x0 = std::max<int>(tri.min_x, work.x0), x1 = std::min<int>(tri.max_x, work.x1 - 1);
  const int y0 = std::max<int>(tri.min_y, work.y0), y1 = std::min<int>(tri.max_y, work.y1 - 1);
  if (x0 > x1 || y0 > y1) return;
  const bool less = state.depth_func == DepthFunc::less, lequal = state.depth_func == DepthFunc::lequal;
  // Writes under LESS or LEQUAL only lower stored depth, so a full block tightens its bound; writes under any other
  // function may raise it, so the bound must follow them up.
  const bool reject_hidden = depth_test && (less || lequal);
  const bool writes_depth = depth_test && state.depth_write;
  for (int by = y0 & ~(kBlockSize - 1); by <= y1; by += kBlockSize) {
    for (int bx = x0 & ~(kBlockSize - 1); bx <= x1; bx += kBlockSize) {
      const int i0 = std::max(x0 - bx, 0), i1 = std::min(x1 - bx, kBlockSize - 1);
      const int j0 = std::max(y0 - by, 0), j1 = std::min(y1 - by, kBlockSize - 1);
      float& bound =
          work.depth_bounds[(by - work.y0) / kBlockSize * (kTileSize / kBlockSize) + (bx - work.x0) / kBlockSize];
      const auto range = [&]() __attribute__((always_inline)) {
        return raster_block_depth_range(tri, state.depth_offset, bx + i0, by + j0, bx + i1, by + j1);
      };
      // A bound of 1 or more rejects nothing (depths are clamped to 1): most blocks until something covers them.
      if (reject_hidden && bound < 1.0f) {
        const float nearest = range().nearest;
        if (less ? nearest - kDepthBoundMargin >= bound : nearest - kDepthBoundMargin > bound) continue;
      }
      const BlockCoverage covered = cover(bx, by, i0, i1, j0, j1);
      if (writes_depth && (covered.full || (!reject_hidden && covered.any))) {
        const float farthest = std::min(range().farthest + kDepthBoundMargin, 1.0f);
        if (!reject_hidden) {
          if (covered.any) bound = std::max(bound, farthest);
        } else if (covered.full) {
          bound = std::min(bound, farthest);
        }
      }
    }
  }
}

// Shades the covered 2x2 quads of one block, one fragment at a time.
template <Shader S>
[[gnu::always_inline]] inline void shade_block_quads(const ShadeContext<S>& ctx, const TriangleSetup& tri,
                                                     const TileWork& work, int bx, int by, std::uint64_t mask) {
  for (int qy = 0; qy < kBlockSize; qy += 2) {
    const std::uint64_t rows = mask >> (qy * kBlockSize);
    if (!(rows & 0xffff)) continue;
    for (int qx = 0; qx < kBlockSize; qx += 2) {
      const unsigned quad =
          static_cast<unsigned>((rows >> qx) & 3) | static_cast<unsigned>((rows >> (kBlockSize + qx)) & 3) << 2;
      if (quad) shade_quad(ctx, tri, work, bx + qx, by + qy, quad);
    }
  }
}

// Immediate shading: every fragment that passes the depth test is shaded as its triangle is drawn.
template <Shader S>
[[gnu::always_inline]] inline void raster_triangle(const ShadeContext<S>& ctx, const TriangleSetup& tri,
                                                   const TileWork& work) {
  const RenderState& state = *ctx.state;
  raster_blocks(
      tri, work, state.depth_test,
      state, [&](int bx, int by, int i0, int i1, int j0, int j1) __attribute__((always_inline)) {
        const std::uint64_t mask = raster_block_coverage(tri, bx, by, i0, i1, j0, j1);
        if (mask) shade_block_quads(ctx, tri, work, bx, by, mask);
        // A discarding shader may leave covered pixels unwritten: its blocks never count as full.
        return BlockCoverage{mask != 0, mask == ~std::uint64_t{0} && !ShaderTraits<S>::may_discard};
      });
}

}  // namespace facet::detail
