// framebuffer.cpp - colour/depth storage, the deferred per-tile clear, tiles in and out of tile memory.
#include "facet/framebuffer.hpp"

#include "facet/detail/bits.hpp"
#include "facet/detail/dispatch.hpp"
#include "facet/detail/multisample.hpp"
#include "facet/detail/tile_memory.hpp"
#include "facet/renderer.hpp"

#if defined(__x86_64__)
#include <emmintrin.h>
#endif

#include <algorithm>
#include <cmath>
#include <cstring>
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

// A tile's pixel rectangle [x0, x1) x [y0, y1).
struct TileRect {
  int x0, y0, x1, y1;
};

template <class T>
void copy_rect(const T* from, std::size_t from_stride, T* to, std::size_t to_stride, int rows, int columns) {
  for (int y = 0; y < rows; ++y)
    std::memcpy(to + static_cast<std::size_t>(y) * to_stride, from + static_cast<std::size_t>(y) * from_stride,
                static_cast<std::size_t>(columns) * sizeof(T));
}

// copy_rect from tile memory to the framebuffer, with streaming stores where a row allows (x86-64): nothing reads the
// pixels again in the frame, and a plain store would first read each line of the framebuffer from memory only to
// overwrite it. The caller fences (fence_streamed) before the pool's barrier hands the pixels to other threads.
template <class T>
void stream_rect(const T* from, T* to, std::size_t to_stride, int rows, int columns) {
#if defined(__x86_64__)
  static_assert(sizeof(T) == 4);
  const bool whole_vectors = columns % 4 == 0;
  for (int y = 0; y < rows; ++y) {
    const T* in = from + static_cast<std::size_t>(y) * kTileSize;
    T* out = to + static_cast<std::size_t>(y) * to_stride;
    if (!whole_vectors || reinterpret_cast<std::uintptr_t>(out) % 16 != 0) {
      std::memcpy(out, in, static_cast<std::size_t>(columns) * sizeof(T));
      continue;
    }
    for (int x = 0; x < columns; x += 4)
      _mm_stream_si128(reinterpret_cast<__m128i*>(out + x), _mm_load_si128(reinterpret_cast<const __m128i*>(in + x)));
  }
#else
  copy_rect(from, kTileSize, to, to_stride, rows, columns);
#endif
}

void fence_streamed() {
#if defined(__x86_64__)
  _mm_sfence();
#endif
}

// Averages a tile's colour samples into the framebuffer's colour rows (see detail::resolve_row).
void resolve_rect(const std::uint32_t* samples, std::uint32_t* out, std::size_t out_stride, int rows, int columns,
                  int count) {
  detail::at_cpu_level([&]() __attribute__((always_inline)) {
    for (int y = 0; y < rows; ++y) {
      const std::uint32_t* in = samples + static_cast<std::size_t>(y) * kTileSize;
      std::uint32_t* row = out + static_cast<std::size_t>(y) * out_stride;
      constexpr std::size_t kPlane = detail::TileMemory::kPixels;
      switch (count) {
        case 2: detail::resolve_row<2>(in, kPlane, row, columns); break;
        case 4: detail::resolve_row<4>(in, kPlane, row, columns); break;
        default: detail::resolve_row<kMaxSamples>(in, kPlane, row, columns); break;
      }
    }
  });
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
  color_.resize(pixel_count());
  depth_.resize(pixel_count());
  block_max_depth_.assign(bounds_per_sample(), 1.0f);
  // Every tile starts with a clear to colour 0 and depth 1 pending (see color_).
  pending_ = {true, true, 0, 1.0f};
  tile_needs_clear_.assign(static_cast<std::size_t>(tiles_x_) * tiles_y_, 1);
  tile_holds_clear_.assign(tile_needs_clear_.size(), 0);
}

Framebuffer::~Framebuffer() { detach_recorder(); }

Framebuffer::Framebuffer(Framebuffer&& other)
    : width_(other.width_), height_(other.height_), samples_(other.samples_), tiles_x_(other.tiles_x_),
      tiles_y_(other.tiles_y_) {
  *this = std::move(other);
}

Framebuffer& Framebuffer::operator=(Framebuffer&& other) {
  if (this == &other) return *this;
  detach_recorder();
  // The renderer holds the source's address: its recorded draws are drawn into it before its pixels move.
  if (other.recorder_) other.recorder_->flush_recorded();
  width_ = other.width_, height_ = other.height_, samples_ = other.samples_;
  tiles_x_ = other.tiles_x_, tiles_y_ = other.tiles_y_;
  color_ = std::move(other.color_);
  depth_ = std::move(other.depth_);
  block_max_depth_ = std::move(other.block_max_depth_);
  sample_color_ = std::move(other.sample_color_);
  sample_depth_ = std::move(other.sample_depth_);
  sample_bounds_ = std::move(other.sample_bounds_);
  keep_samples_ = other.keep_samples_;
  keep_depth_ = other.keep_depth_;
  pending_ = other.pending_;
  tile_needs_clear_ = std::move(other.tile_needs_clear_);
  tile_holds_clear_ = std::move(other.tile_holds_clear_);
  held_ = other.held_;
  contents_exposed_ = other.contents_exposed_;
  return *this;
}

// A framebuffer that goes away takes its recorded draws with it: nothing is left to draw into.
void Framebuffer::detach_recorder() {
  if (recorder_) recorder_->drop_recorded();
}

std::vector<std::uint8_t> Framebuffer::rgba8() const {
  const std::span<const std::uint32_t> pixels = color();
  std::vector<std::uint8_t> bytes(pixels.size() * 4);
  for (std::size_t i = 0; i < pixels.size(); ++i)
    for (int c = 0; c < 4; ++c) bytes[i * 4 + c] = static_cast<std::uint8_t>(pixels[i] >> (8 * c));
  return bytes;
}

std::span<std::uint32_t> Framebuffer::mutable_color() {
  settle_before_write();
  contents_exposed_ = true;
  return color_;
}

std::span<float> Framebuffer::mutable_depth() {
  settle_before_write();
  contents_exposed_ = true;
  std::fill(block_max_depth_.begin(), block_max_depth_.end(), kUnknownDepthBound);
  std::fill(sample_bounds_.begin(), sample_bounds_.end(), kUnknownDepthBound);
  return depth_;
}

void Framebuffer::settle_before_write() {
  if (recorder_) recorder_->flush_recorded();
  if (std::find(tile_needs_clear_.begin(), tile_needs_clear_.end(), 1) != tile_needs_clear_.end())
    resolve_all_clears();
}

void Framebuffer::keep_samples(bool keep) {
  keep_samples_ = keep && samples_ > 1;
  if (keep_samples_ == holds_samples()) return;
  settle_before_write();
  if (!keep_samples_) {
    sample_color_ = {};
    sample_depth_ = {};
    sample_bounds_ = {};
    return;
  }
  hold_sample_planes();
}

void Framebuffer::hold_sample_planes() {
  if (holds_samples()) return;
  // Until a frame draws them, every sample holds what the pixel shows. A tile's pending clear is what loading it
  // gives every sample, so its part of the planes is neither copied nor touched: planes taken at the start of a
  // frame cost memory only where parts of the frame store tiles.
  sample_color_.resize(pixel_count() * static_cast<std::size_t>(samples_));
  sample_depth_.resize(pixel_count() * static_cast<std::size_t>(samples_));
  sample_bounds_.resize(bounds_per_sample() * static_cast<std::size_t>(samples_));
  for (int tile = 0; tile < tiles_x_ * tiles_y_; ++tile) {
    const bool cleared = tile_needs_clear_[static_cast<std::size_t>(tile)] != 0;
    const int x0 = (tile % tiles_x_) * kTileSize, y0 = (tile / tiles_x_) * kTileSize;
    const int columns = std::min(kTileSize, width_ - x0), rows = std::min(kTileSize, height_ - y0);
    const std::size_t first = static_cast<std::size_t>(y0) * width_ + x0;
    const std::size_t bounds = static_cast<std::size_t>(tile) * detail::kTileBlocks;
    for (int s = 0; s < samples_; ++s) {
      const std::size_t plane = static_cast<std::size_t>(s) * pixel_count();
      if (!(cleared && pending_.color))
        copy_rect(color_.data() + first, width_, sample_color_.data() + plane + first, width_, rows, columns);
      if (!(cleared && pending_.depth)) {
        copy_rect(depth_.data() + first, width_, sample_depth_.data() + plane + first, width_, rows, columns);
        std::copy_n(block_max_depth_.data() + bounds, detail::kTileBlocks,
                    sample_bounds_.data() + static_cast<std::size_t>(s) * bounds_per_sample() + bounds);
      }
    }
  }
}

std::span<const std::uint32_t> Framebuffer::sample_color(int sample) const {
  if (sample < 0 || sample >= samples_)
    throw std::out_of_range("sample " + std::to_string(sample) + " of a framebuffer with " +
                            std::to_string(samples_) + " samples per pixel");
  if (samples_ == 1) return color_;
  if (!holds_samples())
    throw std::logic_error("sample_color: the framebuffer does not keep its samples; call keep_samples(true) "
                           "before drawing the frame");
  return std::span<const std::uint32_t>(sample_color_)
      .subspan(static_cast<std::size_t>(sample) * pixel_count(), pixel_count());
}

void Framebuffer::request_clear(glm::vec4 color, float depth, bool clear_color, bool clear_depth) {
  // A clear that leaves a channel of the pending one alone cannot replace it: apply the old one first.
  const bool any_pending = std::find(tile_needs_clear_.begin(), tile_needs_clear_.end(), 1) != tile_needs_clear_.end();
  if (any_pending && ((pending_.color && !clear_color) || (pending_.depth && !clear_depth))) resolve_all_clears();
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
  const std::size_t first = static_cast<std::size_t>(y0) * width_ + x0;
  const int planes = holds_samples() ? samples_ : 0;
  if (pending_.color) {
    fill_color(color_.data() + first, width_, y1 - y0, x1 - x0, pending_.color_value);
    for (int s = 0; s < planes; ++s)
      fill_color(sample_color_.data() + s * pixel_count() + first, width_, y1 - y0, x1 - x0, pending_.color_value);
  }
  if (pending_.depth) {
    fill_depth(depth_.data() + first, width_, y1 - y0, x1 - x0, pending_.depth_value);
    for (int s = 0; s < planes; ++s)
      fill_depth(sample_depth_.data() + s * pixel_count() + first, width_, y1 - y0, x1 - x0, pending_.depth_value);
    reset_depth_bounds(tile_index, pending_.depth_value);
  }
  tile_holds_clear_[tile_index] = held_.color;
}

void Framebuffer::reset_depth_bounds(int tile_index, float value) {
  const std::size_t first = static_cast<std::size_t>(tile_index) * detail::kTileBlocks;
  std::fill_n(block_max_depth_.data() + first, detail::kTileBlocks, value);
  if (holds_samples())
    for (int s = 0; s < samples_; ++s)
      std::fill_n(sample_bounds_.data() + s * bounds_per_sample() + first, detail::kTileBlocks, value);
}

void Framebuffer::resolve_clear_tile_row(int tile_row) {
  const int first = tile_row * tiles_x_, last = first + tiles_x_;
  const int y0 = tile_row * kTileSize, y1 = std::min(y0 + kTileSize, height_);
  const int planes = holds_samples() ? samples_ : 0;
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
    const std::uint32_t depth_bits = detail::bit_cast<std::uint32_t>(pending_.depth_value);
    for (int y = y0; y < y0 + fills; ++y) {
      const std::size_t offset = static_cast<std::size_t>(y) * width_ + x0;
      if (pending_.color) fill_words(color_.data() + offset, count, pending_.color_value);
      if (pending_.depth) fill_words(depth_.data() + offset, count, depth_bits);
      for (int s = 0; s < planes; ++s) {
        if (pending_.color) fill_words(sample_color_.data() + s * pixel_count() + offset, count, pending_.color_value);
        if (pending_.depth) fill_words(sample_depth_.data() + s * pixel_count() + offset, count, depth_bits);
      }
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

void Framebuffer::discard_depth() {
  pending_ = {false, true, 0, 1.0f};
  held_ = {};
  std::fill(tile_holds_clear_.begin(), tile_holds_clear_.end(), std::uint8_t{0});
  std::fill(tile_needs_clear_.begin(), tile_needs_clear_.end(), std::uint8_t{1});
}

void Framebuffer::throw_depth_discarded() {
  throw std::logic_error("depth: the framebuffer does not keep its depth after finish(); call keep_depth(true) "
                         "before drawing the frame");
}

void Framebuffer::load_tile(int tile_index, detail::TileMemory& memory) {
  const int x0 = (tile_index % tiles_x_) * kTileSize, y0 = (tile_index / tiles_x_) * kTileSize;
  const int columns = std::min(kTileSize, width_ - x0), rows = std::min(kTileSize, height_ - y0);
  const std::size_t first = static_cast<std::size_t>(y0) * width_ + x0;
  const std::size_t bounds = static_cast<std::size_t>(tile_index) * detail::kTileBlocks;
  const bool cleared = tile_needs_clear_[tile_index] != 0;
  const bool planes = holds_samples();
  memory.reserve(samples_);
  for (int s = 0; s < samples_; ++s) {
    const std::size_t plane = planes ? static_cast<std::size_t>(s) * pixel_count() : 0;
    if (!(cleared && pending_.color))
      copy_rect((planes ? sample_color_.data() : color_.data()) + plane + first, width_, memory.color_of(s),
                kTileSize, rows, columns);
    if (cleared && pending_.depth) {
      std::fill_n(memory.bounds_of(s), detail::kTileBlocks, pending_.depth_value);
    } else {
      copy_rect((planes ? sample_depth_.data() : depth_.data()) + plane + first, width_, memory.depth_of(s),
                kTileSize, rows, columns);
      const float* from =
          planes ? sample_bounds_.data() + s * bounds_per_sample() + bounds : block_max_depth_.data() + bounds;
      std::copy_n(from, detail::kTileBlocks, memory.bounds_of(s));
    }
  }
  // A pending clear stays lazy: the tile's draws write it (TileWork::lazy_clear), or store_tile does.
  memory.lazy_clear = {cleared && pending_.color, cleared && pending_.depth, pending_.color_value,
                       pending_.depth_value};
  tile_needs_clear_[tile_index] = 0;
  tile_holds_clear_[tile_index] = 0;
}

void Framebuffer::store_tile(int tile_index, const detail::TileMemory& memory, bool store_depth) {
  const int x0 = (tile_index % tiles_x_) * kTileSize, y0 = (tile_index / tiles_x_) * kTileSize;
  const int columns = std::min(kTileSize, width_ - x0), rows = std::min(kTileSize, height_ - y0);
  const std::size_t first = static_cast<std::size_t>(y0) * width_ + x0;
  const std::size_t bounds = static_cast<std::size_t>(tile_index) * detail::kTileBlocks;
  // Planes no draw wrote still hold the clear: it goes straight to the framebuffer.
  const detail::PendingClear& lazy = memory.lazy_clear;
  if (lazy.color) fill_color(color_.data() + first, width_, rows, columns, lazy.color_value);
  else if (samples_ == 1) stream_rect(memory.color_of(0), color_.data() + first, width_, rows, columns);
  else resolve_rect(memory.color_of(0), color_.data() + first, width_, rows, columns, samples_);
  if (store_depth && lazy.depth) fill_depth(depth_.data() + first, width_, rows, columns, lazy.depth_value);
  else if (store_depth) stream_rect(memory.depth_of(0), depth_.data() + first, width_, rows, columns);
  std::copy_n(memory.bounds_of(0), detail::kTileBlocks, block_max_depth_.data() + bounds);
  if (holds_samples())
    for (int s = 0; s < samples_; ++s) {
      std::uint32_t* color = sample_color_.data() + static_cast<std::size_t>(s) * pixel_count() + first;
      float* depth = sample_depth_.data() + static_cast<std::size_t>(s) * pixel_count() + first;
      if (lazy.color) fill_color(color, width_, rows, columns, lazy.color_value);
      else copy_rect(memory.color_of(s), kTileSize, color, width_, rows, columns);
      if (!store_depth) continue;
      if (lazy.depth) fill_depth(depth, width_, rows, columns, lazy.depth_value);
      else copy_rect(memory.depth_of(s), kTileSize, depth, width_, rows, columns);
      std::copy_n(memory.bounds_of(s), detail::kTileBlocks, sample_bounds_.data() + s * bounds_per_sample() + bounds);
    }
  fence_streamed();
}

}  // namespace facet
