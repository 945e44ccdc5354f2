// raster_deferred.hpp - deferred shading of one tile: a visibility pass over all its triangles, then one shading pass.
#pragma once

#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>

#include "facet/fragment_lanes.hpp"
#include "facet/simd.hpp"
#include "facet/detail/raster.hpp"

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"

namespace facet::detail {

// Tile-based deferred shading, as PowerVR-style GPUs do it. When the fragment shader cannot discard and colour is
// written without blending, a pixel's final colour is the colour of the last fragment that passed the depth test
// there, and fragment shaders have no side effects. So the tile first runs coverage and the depth test for all of
// its triangles, in draw order, keeping per pixel the triangle that passed last; then it shades each pixel once,
// with that triangle. The image (colours, depth, derivatives, fill rule) is bit-identical to shading as the
// triangles come, but overdraw costs a depth test instead of a fragment shader.

inline std::size_t scratch_index(int block_x, int block_y) {
  return static_cast<std::size_t>(block_y * (kTileSize / kScratchBlock) + block_x) * kScratchBlock * kScratchBlock;
}

inline simd::Mask depth_passes(DepthFunc func, simd::Float fragment, simd::Float stored) {
  switch (func) {
    case DepthFunc::never: return simd::Mask{};
    case DepthFunc::less: return fragment < stored;
    case DepthFunc::equal: return fragment == stored;
    case DepthFunc::lequal: return fragment <= stored;
    case DepthFunc::greater: return fragment > stored;
    case DepthFunc::notequal: return fragment != stored;
    case DepthFunc::gequal: return fragment >= stored;
    case DepthFunc::always: return simd::splat(-1);
  }
  return simd::Mask{};
}

// A plane at the 16 pixel centres of the strip whose top-left pixel is (px, py): the same float operations, in the
// same order, as evaluate() and shade_quad's per-pixel offsets, so lanes and scalar code agree bit for bit.
struct StripCentres {
  simd::Float x, y, dx, dy;
  StripCentres(const TriangleSetup& tri, int px, int py)
      : x(simd::to_float(simd::kLaneX + px) + 0.5f),
        y(simd::to_float(simd::kLaneY + py) + 0.5f),
        dx(x - tri.origin_x),
        dy(y - tri.origin_y) {}
  FACET_LANES_INLINE simd::Float evaluate(const Plane& p) const { return simd::splat(p.at_origin) + p.ddx * dx + p.ddy * dy; }
};

// Visibility pass, one block: the depth test of the covered pixels against the tile's local depth, and the
// triangle reference of those that pass.
[[gnu::always_inline]] inline void raster_block_visibility(const TriangleSetup& tri, const RenderState& state,
                                                           const TileWork& work, int bx, int by, std::uint64_t mask,
                                                           std::uint32_t ref) {
  const std::size_t block = scratch_index((bx - work.x0) / kScratchBlock, (by - work.y0) / kScratchBlock);
  float* depth = work.scratch->depth + block;
  std::uint32_t* triangle = work.scratch->triangle + block;
  for (int strip = 0; strip < kScratchBlock / 2; ++strip) {
    const unsigned bits = static_cast<unsigned>(mask >> (strip * simd::kLanes)) & 0xffffu;
    if (!bits) continue;
    simd::Mask pass = simd::mask_from_bits(bits);
    const std::size_t at = static_cast<std::size_t>(strip) * simd::kLanes;
    if (state.depth_test) {
      const StripCentres centres(tri, bx, by + 2 * strip);
      const simd::Float z = simd::clamp(centres.evaluate(tri.depth) + state.depth_offset, 0.0f, 1.0f);
      const simd::Float stored = simd::load<simd::Float>(depth + at);
      pass &= depth_passes(state.depth_func, z, stored);
      if (state.depth_write) simd::store(depth + at, simd::select(pass, z, stored));
    }
    const simd::UInt previous = simd::load<simd::UInt>(triangle + at);
    simd::store(triangle + at, simd::select(pass, simd::UInt{} + ref, previous));
  }
}

// Writes the packed colours of the lanes set in `bits` to the strip's two framebuffer rows.
[[gnu::always_inline]] inline void store_strip(const TileWork& work, int px, int py, unsigned bits,
                                               const simd::UInt& packed) {
  alignas(64) std::uint32_t colors[simd::kLanes];
  simd::store(colors, packed);
  for (int row = 0; row < 2; ++row) {
    std::uint32_t* out = work.color + static_cast<std::size_t>(py + row) * work.stride + px;
    const unsigned row_bits = (bits >> (row * 8)) & 0xffu;
    if (row_bits == 0xffu) {
      std::memcpy(out, colors + row * 8, 8 * sizeof(std::uint32_t));
      continue;
    }
    for (unsigned b = row_bits; b; b &= b - 1) {
      const int i = std::countr_zero(b);
      out[i] = colors[row * 8 + i];
    }
  }
}

// Shading pass, one strip of a LaneShader: perspective-correct varyings for 16 pixels, one fragment_lanes call.
template <LaneShader S>
[[gnu::always_inline]] inline void shade_strip_lanes(const ShadeContext<S>& ctx, const TriangleSetup& tri,
                                                     const TileWork& work, int px, int py, unsigned bits) {
  using namespace simd;
  using Varyings = typename S::Varyings;
  constexpr std::size_t kFloats = float_count_v<Varyings>;
  const StripCentres centres(tri, px, py);
  FragmentLanes<Varyings> fragment;
  fragment.screen_x = centres.x;
  fragment.screen_y = centres.y;
  fragment.depth = clamp(centres.evaluate(tri.depth) + ctx.state->depth_offset, 0.0f, 1.0f);
  fragment.active = mask_from_bits(bits);
  fragment.primitive = tri.primitive;
  fragment.front_facing = tri.front_facing;
  const Float w = 1.0f / centres.evaluate(tri.inv_w);
  const Float b1 = centres.evaluate(tri.b1_over_w) * w, b2 = centres.evaluate(tri.b2_over_w) * w;
  const float* v0 = ctx.varyings + std::size_t{tri.vertex[0]} * kFloats;
  const float* v1 = ctx.varyings + std::size_t{tri.vertex[1]} * kFloats;
  const float* v2 = ctx.varyings + std::size_t{tri.vertex[2]} * kFloats;
  for (std::size_t f = 0; f < kFloats; ++f) {
    const Float value = v0[f] + b1 * (v1[f] - v0[f]) + b2 * (v2[f] - v0[f]);
    fragment.varyings[f] = value;
    if constexpr (needs_derivatives<S>()) {
      const Float origin = quad_broadcast(value, kQuadTopLeft);
      fragment.ddx[f] = quad_broadcast(value, kQuadTopRight) - origin;
      fragment.ddy[f] = quad_broadcast(value, kQuadBottomLeft) - origin;
    }
  }
  store_strip(work, px, py, bits, pack_rgba8(ctx.shader->fragment_lanes(fragment)));
}

// Shading pass, the pixels of one block that `tri` drew last.
template <Shader S>
[[gnu::always_inline]] inline void shade_block_deferred(const ShadeContext<S>& ctx, const TriangleSetup& tri,
                                                        const TileWork& work, int bx, int by, std::uint64_t mask) {
  if constexpr (LaneShader<S>) {
    for (int strip = 0; strip < kScratchBlock / 2; ++strip) {
      const unsigned bits = static_cast<unsigned>(mask >> (strip * simd::kLanes)) & 0xffffu;
      if (bits) shade_strip_lanes(ctx, tri, work, bx, by + 2 * strip, bits);
    }
  } else {
    shade_block_quads(ctx, tri, work, bx, by, mask);  // ctx's state has the depth test off: it is resolved
  }
}

template <Shader S>
[[gnu::always_inline]] inline void raster_tile_deferred(const ShadeContext<S>& ctx, const TileWork& work) {
  const RenderState& state = *ctx.state;
  TileScratch& scratch = *work.scratch;
  const int width = work.x1 - work.x0, height = work.y1 - work.y0;
  const bool local_depth = state.depth_test || work.depth_cleared;

  // The tile's depth comes in from the framebuffer unless it is being cleared.
  if (local_depth) {
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; x += kScratchBlock) {
        float* local = scratch.depth + scratch_index(x / kScratchBlock, y / kScratchBlock) + (y % kScratchBlock) * kScratchBlock;
        const float* global = work.depth + static_cast<std::size_t>(work.y0 + y) * work.stride + work.x0 + x;
        const int n = std::min(kScratchBlock, width - x);
        if (work.depth_cleared) std::fill_n(local, n, work.clear_depth);
        else std::memcpy(local, global, static_cast<std::size_t>(n) * sizeof(float));
      }
  }
  std::fill_n(scratch.triangle, kTileSize * kTileSize, kNoTriangle);

  for (std::size_t c = 0; c < work.chunk_count; ++c) {
    const SetupChunk& chunk = work.chunks[c];
    for (std::uint32_t i = chunk.first[work.tile]; i < chunk.first[work.tile + 1]; ++i) {
      const std::uint32_t index = chunk.binned[i];
      const TriangleSetup& tri = chunk.triangles[index];
      const std::uint32_t ref = triangle_ref(c, index);
      raster_triangle_blocks<false>(tri, work, state, [&](int bx, int by, std::uint64_t mask) {
        raster_block_visibility(tri, state, work, bx, by, mask, ref);
      });
    }
  }

  RenderState resolved = state;
  resolved.depth_test = false;
  const ShadeContext<S> shade{ctx.shader, ctx.varyings, &resolved};
  for (int block_y = 0; block_y * kScratchBlock < height; ++block_y)
    for (int block_x = 0; block_x * kScratchBlock < width; ++block_x) {
      const std::uint32_t* triangle = scratch.triangle + scratch_index(block_x, block_y);
      std::uint64_t pending = 0;
      for (int k = 0; k < 64; ++k) pending |= std::uint64_t{triangle[k] != kNoTriangle} << k;
      while (pending) {
        const std::uint32_t ref = triangle[std::countr_zero(pending)];
        std::uint64_t same = 0;
        for (int k = 0; k < 64; ++k) same |= std::uint64_t{triangle[k] == ref} << k;
        pending &= ~same;
        const TriangleSetup& tri = work.chunks[ref >> kTriangleIndexBits].triangles[ref & ((1u << kTriangleIndexBits) - 1)];
        shade_block_deferred(shade, tri, work, work.x0 + block_x * kScratchBlock, work.y0 + block_y * kScratchBlock, same);
      }
    }

  if (work.depth_cleared || (state.depth_test && state.depth_write)) {
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; x += kScratchBlock) {
        const float* local = scratch.depth + scratch_index(x / kScratchBlock, y / kScratchBlock) + (y % kScratchBlock) * kScratchBlock;
        float* global = work.depth + static_cast<std::size_t>(work.y0 + y) * work.stride + work.x0 + x;
        std::memcpy(global, local, static_cast<std::size_t>(std::min(kScratchBlock, width - x)) * sizeof(float));
      }
  }
}

}  // namespace facet::detail

#pragma GCC diagnostic pop
