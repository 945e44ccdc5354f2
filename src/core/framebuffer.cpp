// framebuffer.cpp - colour/depth storage and the deferred per-tile clear.
#include "facet/framebuffer.hpp"

#include "facet/detail/bits.hpp"
#include "facet/detail/dispatch.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace facet {
namespace {

// Clears are pure store bandwidth: compiled per CPU level like the hot loops (detail/dispatch.hpp), so a portable
// build still writes 32 or 64 bytes per store where the CPU can.
template <class T>
void fill_rect(T* first, std::size_t stride, int rows, int columns, T value) {
  detail::at_cpu_level([&]() __attribute__((always_inline)) {
    for (int y = 0; y < rows; ++y) {
      T* row = first + static_cast<std::size_t>(y) * stride;
      for (int x = 0; x < columns; ++x) row[x] = value;
    }
  });
}

void fill_color(std::uint32_t* first, std::size_t stride, int rows, int columns, std::uint32_t value) {
  fill_rect(first, stride, rows, columns, value);
}

void fill_depth(float* first, std::size_t stride, int rows, int columns, float value) {
  fill_rect(first, stride, rows, columns, value);
}

// A contiguous fill of 32-bit values. On x86-64 `rep stosd` uses the CPU's fast-string path, which writes whole
// cache lines without reading them first; vector stores would read each line in before overwriting it.
void fill_words(void* first, std::size_t count, std::uint32_t value) {
#if defined(__x86_64__) && !defined(FACET_NO_DISPATCH)
  asm volatile("rep stosl" : "+D"(first), "+c"(count) : "a"(value) : "memory");
#else
  std::fill_n(static_cast<std::uint32_t*>(first), count, value);
#endif
}

}  // namespace

Framebuffer::Framebuffer(int width, int height, int samples) : width_(width), height_(height), samples_(samples) {
  if (width < 1 || height < 1 || width > kMaxDimension || height > kMaxDimension)
    throw std::invalid_argument("framebuffer size " + std::to_string(width) + "x" + std::to_string(height) +
                                " is outside 1.." + std::to_string(kMaxDimension));
  if (samples != 1 && samples != 2 && samples != 4 && samples != 8)
    throw std::invalid_argument("samples per pixel must be 1, 2, 4 or 8, not " + std::to_string(samples));
  tiles_x_ = (width + kTileSize - 1) / kTileSize;
  tiles_y_ = (height + kTileSize - 1) / kTileSize;
  color_.resize(pixel_count() * static_cast<std::size_t>(samples));
  depth_.resize(pixel_count() * static_cast<std::size_t>(samples));
  if (samples > 1) resolved_.resize(pixel_count());
  block_max_depth_.assign(bounds_per_sample() * static_cast<std::size_t>(samples), 1.0f);
  // Every tile starts with a clear to colour 0 and depth 1 pending (see color_).
  pending_ = {true, true, 0, 1.0f};
  tile_needs_clear_.assign(static_cast<std::size_t>(tiles_x_) * tiles_y_, 1);
  tile_holds_clear_.assign(tile_needs_clear_.size(), 0);
}

std::vector<std::uint8_t> Framebuffer::rgba8() const {
  const std::span<const std::uint32_t> pixels = color();
  std::vector<std::uint8_t> bytes(pixels.size() * 4);
  for (std::size_t i = 0; i < pixels.size(); ++i)
    for (int c = 0; c < 4; ++c) bytes[i * 4 + c] = static_cast<std::uint8_t>(pixels[i] >> (8 * c));
  return bytes;
}

void Framebuffer::request_clear(glm::vec4 color, float depth, bool clear_color, bool clear_depth) {
  // A clear of other channels than the pending one cannot be merged into it: apply the old one first.
  const bool any_pending = std::find(tile_needs_clear_.begin(), tile_needs_clear_.end(), 1) != tile_needs_clear_.end();
  if (any_pending && (pending_.color != clear_color || pending_.depth != clear_depth)) resolve_all_clears();
  pending_ = {clear_color, clear_depth, pack_rgba8(color), depth};
  // Tiles keep their mark only for a clear of both channels to the very values they hold, and only if nobody
  // could have written to them since. Depths compare bit for bit.
  const bool same_as_held =
      !contents_exposed_ && clear_color && clear_depth && held_.color && held_.depth &&
      held_.color_value == pending_.color_value &&
      detail::bit_cast<std::uint32_t>(held_.depth_value) == detail::bit_cast<std::uint32_t>(depth);
  if (!same_as_held) std::fill(tile_holds_clear_.begin(), tile_holds_clear_.end(), std::uint8_t{0});
  held_ = clear_color && clear_depth ? pending_ : detail::PendingClear{};
  contents_exposed_ = false;
  for (std::size_t t = 0; t < tile_needs_clear_.size(); ++t) tile_needs_clear_[t] = tile_holds_clear_[t] ? 0 : 1;
}

void Framebuffer::resolve_clear(int tile_index) {
  if (!tile_needs_clear_[tile_index]) return;
  tile_needs_clear_[tile_index] = 0;
  const int x0 = (tile_index % tiles_x_) * kTileSize, y0 = (tile_index / tiles_x_) * kTileSize;
  const int x1 = std::min(x0 + kTileSize, width_), y1 = std::min(y0 + kTileSize, height_);
  for (int s = 0; s < samples_; ++s) {
    const std::size_t first = sample_offset(s) + static_cast<std::size_t>(y0) * width_ + x0;
    if (pending_.color) fill_color(color_.data() + first, width_, y1 - y0, x1 - x0, pending_.color_value);
    if (pending_.depth) fill_depth(depth_.data() + first, width_, y1 - y0, x1 - x0, pending_.depth_value);
  }
  if (pending_.color && samples_ > 1)
    fill_color(resolved_.data() + static_cast<std::size_t>(y0) * width_ + x0, width_, y1 - y0, x1 - x0,
               pending_.color_value);
  if (pending_.depth) reset_depth_bounds(tile_index, pending_.depth_value);
  tile_holds_clear_[tile_index] = held_.color;
}

detail::PendingClear Framebuffer::begin_tile_draw(int tile_index, bool deferred) {
  if (!deferred) resolve_clear(tile_index);
  tile_holds_clear_[tile_index] = 0;
  if (!deferred || !tile_needs_clear_[tile_index]) return {};
  tile_needs_clear_[tile_index] = 0;
  if (pending_.depth) reset_depth_bounds(tile_index, pending_.depth_value);
  return pending_;
}

void Framebuffer::reset_depth_bounds(int tile_index, float value) {
  for (int s = 0; s < samples_; ++s)
    std::fill_n(tile_depth_bounds(tile_index) + static_cast<std::size_t>(s) * bounds_per_sample(), kTileBlocks, value);
}

void Framebuffer::resolve_clear_tile_row(int tile_row) {
  const int first = tile_row * tiles_x_, last = first + tiles_x_;
  const int y0 = tile_row * kTileSize, y1 = std::min(y0 + kTileSize, height_);
  // Runs of neighbouring tiles still to clear. A run across the whole width (the common case at finish() after an
  // empty or sparse frame) is contiguous in memory and takes one fill; a run beside drawn tiles takes one fill per
  // pixel row, rather than a strided fill per tile.
  for (int t = first; t < last;) {
    if (!tile_needs_clear_[t]) {
      ++t;
      continue;
    }
    int end = t + 1;
    while (end < last && tile_needs_clear_[end]) ++end;
    const int x0 = (t - first) * kTileSize, x1 = std::min((end - first) * kTileSize, width_);
    const bool whole_rows = x0 == 0 && x1 == width_;
    const int fills = whole_rows ? 1 : y1 - y0;
    const std::size_t count = static_cast<std::size_t>(x1 - x0) * (whole_rows ? y1 - y0 : 1);
    for (int s = 0; s < samples_; ++s)
      for (int y = y0; y < y0 + fills; ++y) {
        const std::size_t offset = sample_offset(s) + static_cast<std::size_t>(y) * width_ + x0;
        if (pending_.color) fill_words(color_.data() + offset, count, pending_.color_value);
        if (pending_.depth)
          fill_words(depth_.data() + offset, count, detail::bit_cast<std::uint32_t>(pending_.depth_value));
        if (pending_.color && samples_ > 1 && s == 0)
          fill_words(resolved_.data() + offset, count, pending_.color_value);
      }
    for (; t < end; ++t) {
      tile_needs_clear_[t] = 0;
      tile_holds_clear_[t] = held_.color;
      if (pending_.depth) reset_depth_bounds(t, pending_.depth_value);
    }
  }
}

void Framebuffer::resolve_all_clears() {
  for (int t = 0; t < tiles_x_ * tiles_y_; ++t) resolve_clear(t);
  pending_ = {};
}

}  // namespace facet
