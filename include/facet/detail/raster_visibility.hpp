// raster_visibility.hpp - deferred shading's visibility pass: coverage and depth of a tile's triangles.
#pragma once

#include <cstddef>
#include <cstdint>

#include "facet/detail/raster.hpp"
#include "facet/render_state.hpp"

namespace facet::detail {

inline std::size_t scratch_index(int block_x, int block_y) {
  return static_cast<std::size_t>(block_y * (kTileSize / kScratchBlock) + block_x) * kScratchBlock * kScratchBlock;
}

// Triangles whose pixel bounds span at most this many pixels each way have all their edge values, over every block
// they touch, within 32 bits: their snapped vertices lie within 2 pixels of the bounds (snap_to_subpixel clamps to
// one pixel beyond the target), so |a|, |b| <= (span + 4) * 256, and the pixels of those blocks are at most
// span + 10 pixels from each vertex, which bounds |a * i + b * j + q| by 2 * (span + 4) * 256 * (span + 10) < 2^30
// for span 1024.
inline constexpr int kSmallTriangleSpan = 1024;

// Visibility pass of one tile: coverage and depth of all its triangles, in draw order, keeping per pixel in the
// tile's scratch the triangle that passed last. It touches no varyings, so it is compiled once per CPU level in the
// library (src/core/raster_visibility.cpp) rather than once per shader.
void raster_tile_visibility(const RenderState& state, const TileWork& work);

// The same for a multisampled tile: planes[s] (sample_work) is sample s's plane, which sees each triangle through
// at_sample; triangles in draw order, each tested against every sample plane.
void raster_tile_visibility_multisample(const RenderState& state, const TileWork& work, const TileWork* planes);

}  // namespace facet::detail
