// tile_memory.hpp - one thread's copy of the tile it rasterizes: every sample's colour, depth and depth bounds.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "facet/detail/binning.hpp"
#include "facet/framebuffer.hpp"

namespace facet::detail {

// A frame's draws are recorded, then each tile is rasterized once with all of them (Renderer::finish): the tile's
// samples live here, in memory the thread owns and reuses tile after tile, so they stay in its cache, and the
// framebuffer receives only the tile's final pixels. Rows are kTileSize pixels apart whatever the tile's width;
// sample s's plane starts at s * kPixels, its kTileBlocks depth bounds at s * kTileBlocks.
struct TileMemory {
  static constexpr std::size_t kPixels = std::size_t{kTileSize} * kTileSize;
  template <class T>
  using Storage = std::vector<T, CacheAlignedAllocator<T>>;

  Storage<std::uint32_t> color;
  Storage<float> depth;
  Storage<float> bounds;
  PendingClear lazy_clear;  // planes not yet written: all the tile's clear (TileWork::lazy_clear)

  void reserve(int samples) {
    const std::size_t n = static_cast<std::size_t>(samples);
    if (color.size() >= n * kPixels) return;
    color.resize(n * kPixels);
    depth.resize(n * kPixels);
    bounds.resize(n * static_cast<std::size_t>(kTileBlocks));
  }
  std::uint32_t* color_of(int sample) { return color.data() + static_cast<std::size_t>(sample) * kPixels; }
  float* depth_of(int sample) { return depth.data() + static_cast<std::size_t>(sample) * kPixels; }
  float* bounds_of(int sample) { return bounds.data() + static_cast<std::size_t>(sample) * kTileBlocks; }
  const std::uint32_t* color_of(int sample) const {
    return color.data() + static_cast<std::size_t>(sample) * kPixels;
  }
  const float* depth_of(int sample) const { return depth.data() + static_cast<std::size_t>(sample) * kPixels; }
  const float* bounds_of(int sample) const { return bounds.data() + static_cast<std::size_t>(sample) * kTileBlocks; }
};

}  // namespace facet::detail
