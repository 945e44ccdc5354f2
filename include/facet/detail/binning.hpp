// binning.hpp - the frame's work between setup and rasterization: set-up primitives and per-tile bins.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "facet/detail/triangle_setup.hpp"

namespace facet::detail {

// Setup runs over fixed-size chunks of primitives, whatever the thread count, and each chunk bins into its own
// lists. A tile then walks the chunks in order, so it sees its triangles in draw order with no locks and the image
// is identical at any thread count.
inline constexpr std::size_t kSetupChunk = 4096;     // primitives per setup task
inline constexpr std::size_t kChunksPerBatch = 64;   // setup memory is bounded by one batch at a time

struct SetupChunk {
  std::vector<TriangleSetup> triangles;
  std::vector<std::vector<std::uint32_t>> bins;  // per tile: indices into `triangles`
  std::size_t culled = 0, clipped = 0, invalid = 0;

  void reset(std::size_t tiles) {
    triangles.clear();
    if (bins.size() != tiles) bins.resize(tiles);
    for (auto& bin : bins) bin.clear();
    culled = clipped = invalid = 0;
  }
};

// One tile's share of a batch, handed to the shader-specific rasterizer.
struct TileWork {
  int tile;
  int x0, y0, x1, y1;  // pixel rectangle [x0, x1) x [y0, y1)
  int stride;          // pixels per framebuffer row
  std::uint32_t* color;
  float* depth;
  const SetupChunk* chunks;
  std::size_t chunk_count;
};

}  // namespace facet::detail
