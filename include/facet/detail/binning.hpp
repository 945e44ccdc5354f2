// binning.hpp - the frame's work between setup and rasterization: set-up primitives and per-tile bins.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

#include "facet/detail/default_init.hpp"
#include "facet/detail/triangle_setup.hpp"
#include "facet/framebuffer.hpp"

namespace facet::detail {

// Setup runs over chunks of primitives, cut the same whatever the thread count, and each chunk bins into its own
// lists. A tile then walks the chunks in order, so it sees its triangles in draw order with no locks and the image
// is identical at any thread count.
inline constexpr std::size_t kSetupChunk = 4096;  // primitives per setup task
// Setup memory is bounded by one batch at a time. 16 chunks (65,536 primitives) keep a dense mesh's set-up
// triangles and varyings of a batch near the cache while its tiles read them back: on sphere:1414, 64 chunks were
// 14% slower at 2 threads, 8 chunks 2-5% slower (more tile visits and barriers per frame).
inline constexpr std::size_t kChunksPerBatch = 16;
// A draw of fewer than 8 full chunks is cut into 8 smaller ones of at least kMinSetupChunk primitives, so that a
// small mesh's setup is shared between threads instead of leaving all but one waiting (WusonOBJ: 3,732 triangles,
// one chunk). The size depends on the draw alone, not the thread count: the chunks are walked in order, so the
// image is the same either way.
inline constexpr std::size_t kMinSetupChunk = 512;
inline std::size_t setup_chunk_size(std::size_t primitives) {
  return std::clamp<std::size_t>((primitives + 7) / 8, kMinSetupChunk, kSetupChunk);
}

// A chunk's bins are one flat array sorted by tile (a counting sort after setup): tile t's triangles are
// binned[first[t]] .. binned[first[t + 1] - 1], in draw order. Flat arrays only grow with the number of
// (triangle, tile) pairs, so steady-state frames reuse their memory instead of allocating. Neighbouring chunks are
// set up by different threads at once, and each bumps its own vectors' ends and counters per triangle: a chunk
// starts a cache line so that those writes do not contend.
struct alignas(64) SetupChunk {
  // Setup writes every field of a TriangleSetup in place; value-initialisation would first zero all 136 bytes.
  std::vector<TriangleSetup, DefaultInitAllocator<std::allocator<TriangleSetup>>> triangles;
  std::vector<std::uint32_t> pair_tile, pair_triangle;  // (tile, triangle) pairs in the order setup emits them
  std::vector<std::uint32_t> first;                     // per tile, plus one end marker
  std::vector<std::uint32_t> binned;
  std::size_t culled = 0, clipped = 0, invalid = 0;

  void reset() {
    // Room for a full chunk of small triangles up front, so the counts that wobble from frame to frame as a
    // model turns do not trigger a string of small reallocations.
    if (pair_tile.capacity() < 2 * kSetupChunk) {
      pair_tile.reserve(2 * kSetupChunk);
      pair_triangle.reserve(2 * kSetupChunk);
      binned.reserve(2 * kSetupChunk);
      triangles.reserve(kSetupChunk);
    }
    triangles.clear();
    pair_tile.clear();
    pair_triangle.clear();
    culled = clipped = invalid = 0;
  }
  void add(std::uint32_t tile, std::uint32_t triangle) {
    pair_tile.push_back(tile);
    pair_triangle.push_back(triangle);
  }
  void sort_by_tile(std::size_t tiles) {
    first.assign(tiles + 1, 0);
    for (const std::uint32_t t : pair_tile) ++first[t + 1];
    for (std::size_t t = 0; t < tiles; ++t) first[t + 1] += first[t];
    if (binned.capacity() < pair_tile.size()) binned.reserve(std::max(pair_tile.size(), 2 * binned.capacity()));
    binned.resize(pair_tile.size());
    for (std::size_t i = 0; i < pair_tile.size(); ++i) binned[first[pair_tile[i]]++] = pair_triangle[i];
    // The scatter advanced each start to the next tile's start; shift back.
    for (std::size_t t = tiles; t > 0; --t) first[t] = first[t - 1];
    first[0] = 0;
  }
  std::uint32_t binned_count(std::size_t tile) const { return first[tile + 1] - first[tile]; }
};

// A reference to one set-up triangle of a batch: its chunk in the high bits, its index in the chunk below.
inline constexpr int kTriangleIndexBits = 20;
inline constexpr std::uint32_t kNoTriangle = 0xffffffffu;
// Clipping makes at most 8 triangles of one primitive (a 10-gon), a line makes 2.
static_assert(kSetupChunk * 8 < (std::size_t{1} << kTriangleIndexBits));
static_assert(2 * kChunksPerBatch << kTriangleIndexBits < kNoTriangle);  // a batch holds up to two batches' worth
inline std::uint32_t triangle_ref(std::size_t chunk, std::uint32_t index) {
  return static_cast<std::uint32_t>(chunk) << kTriangleIndexBits | index;
}
// The most chunks one batch can hold, so that a reference never equals kNoTriangle.
inline constexpr std::size_t kMaxChunksPerBatch = (kNoTriangle >> kTriangleIndexBits) - 1;

// Deferred shading's per-thread copy of one tile: depth and, per pixel, the triangle that drew it last. Stored
// block by block (8x8 blocks in row order, pixels in row order within a block), so each 8x2 strip of a block is
// 16 consecutive values: one lane vector. 32 KiB, so a tile's working set stays in the first-level cache.
inline constexpr int kScratchBlock = 8;
struct alignas(64) TileScratch {
  float depth[kTileSize * kTileSize];
  std::uint32_t triangle[kTileSize * kTileSize];
};

// One tile's share of a batch, handed to the shader-specific rasterizer.
struct TileWork {
  int tile;
  int x0, y0, x1, y1;  // pixel rectangle [x0, x1) x [y0, y1)
  // The tile's pixels in the thread's tile memory (TileMemory): pixel (x, y) at (y - y0) * stride + (x - x0).
  int stride;
  std::uint32_t* color;
  float* depth;
  float* depth_bounds;  // kTileBlocks, row-major over the tile's 8x8 blocks
  const SetupChunk* chunks;
  std::size_t chunk_count;
  // The tile's triangles as references (triangle_ref) in the order to draw them, for a batch drawn farthest first
  // (sorted in the tile pass); null for the bins' draw order.
  const std::uint32_t* sorted = nullptr;
  std::size_t sorted_count = 0;
  const float* varyings;  // post-transform varyings, indexed by TriangleSetup::vertex
  TileScratch* scratch;   // the running thread's, for deferred shading: one per sample
  // The tile memory's colour or depth planes that still hold nothing but the tile's pending clear and are not yet
  // written: paths that read or blend them in place settle them first (settle_clear); deferred shading writes the
  // clear colour with its shaded strips and fills its depth scratch with the clear depth, so that a cleared tile's
  // pixels are written once, not filled and then overwritten.
  PendingClear* lazy_clear;
  // Multisampling: samples per pixel, and how far apart the samples' colour and depth planes and depth bounds lie
  // (color, depth and depth_bounds above are sample 0's; see sample_work in multisample.hpp).
  int samples = 1;
  std::size_t sample_stride = 0, bounds_stride = 0;
  // The pixel's place in color and depth (sample 0's plane).
  std::size_t at(int x, int y) const {
    return static_cast<std::size_t>(y - y0) * static_cast<std::size_t>(stride) + static_cast<std::size_t>(x - x0);
  }
};

// Writes the lazy clear into every sample's colour (when `color`) and depth (when `depth`) planes.
inline void settle_clear(const TileWork& work, bool color, bool depth) {
  PendingClear& clear = *work.lazy_clear;
  color = color && clear.color, depth = depth && clear.depth;
  for (int s = 0; s < work.samples && (color || depth); ++s)
    for (int y = work.y0; y < work.y1; ++y) {
      const std::size_t at = work.sample_stride * static_cast<std::size_t>(s) + work.at(work.x0, y);
      if (color) std::fill_n(work.color + at, work.x1 - work.x0, clear.color_value);
      if (depth) std::fill_n(work.depth + at, work.x1 - work.x0, clear.depth_value);
    }
  if (color) clear.color = false;
  if (depth) clear.depth = false;
}

// Calls f(triangle, ref) for each triangle binned to the work's tile, in draw order (chunk by chunk), or in the
// sorted order when the work has one.
template <class F>
[[gnu::always_inline]] inline void for_each_tile_triangle(const TileWork& work, F&& f) {
  if (work.sorted) {
    constexpr std::uint32_t kIndexMask = (std::uint32_t{1} << kTriangleIndexBits) - 1;
    for (std::size_t k = 0; k < work.sorted_count; ++k) {
      const std::uint32_t ref = work.sorted[k];
      f(work.chunks[ref >> kTriangleIndexBits].triangles[ref & kIndexMask], ref);
    }
    return;
  }
  for (std::size_t c = 0; c < work.chunk_count; ++c) {
    const SetupChunk& chunk = work.chunks[c];
    for (std::uint32_t i = chunk.first[work.tile]; i < chunk.first[work.tile + 1]; ++i) {
      const std::uint32_t index = chunk.binned[i];
      f(chunk.triangles[index], triangle_ref(c, index));
    }
  }
}

}  // namespace facet::detail
