// framebuffer.hpp - the render target: RGBA8 colour and float depth per sample, row 0 at the top of the image.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <new>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "facet/detail/default_init.hpp"

namespace facet {

inline constexpr int kTileSize = 64;  // pixels; one thread owns a tile while it is rasterized
inline constexpr int kMaxDimension = 16384;
inline constexpr int kMaxSamples = 8;  // multisampling: 1, 2, 4 or 8 colour and depth samples per pixel

// Packs a colour in [0, 1] as little-endian RGBA8: r in the low byte, rounded to nearest. NaN becomes 0.
inline std::uint32_t pack_channel(float c) {
  const float clamped = c > 0.0f ? (c < 1.0f ? c : 1.0f) : 0.0f;
  return static_cast<std::uint32_t>(clamped * 255.0f + 0.5f);
}
inline std::uint32_t pack_rgba8(glm::vec4 color) {
  return pack_channel(color.r) | pack_channel(color.g) << 8 | pack_channel(color.b) << 16 | pack_channel(color.a) << 24;
}
inline glm::vec4 unpack_rgba8(std::uint32_t rgba) {
  return glm::vec4(rgba & 0xff, (rgba >> 8) & 0xff, (rgba >> 16) & 0xff, rgba >> 24) / 255.0f;
}

namespace detail {
// Memory for large buffers (frame buffers, textures, encoder output): aligned to a cache line, and, from 2 MiB up,
// to 2 MiB and marked for transparent huge pages (madvise MADV_HUGEPAGE), where the system offers them. A fresh
// 4 KiB page costs a fault and the kernel's zeroing; a 1920x1080 target's colour and depth are 4,096 of them (about
// 50 ms on the development machine's virtualised CPU), or 8 huge pages (about 1.5 ms). Throws std::bad_alloc.
void* allocate_buffer(std::size_t bytes);
void free_buffer(void* p) noexcept;
}  // namespace detail

// Storage aligned to a cache line (and large blocks to huge pages, above). Two threads rasterizing neighbouring
// tiles write the pixels on either side of their shared boundary at the same time; with rows of 64-byte multiples
// (widths that are multiples of 16) and an aligned start, no cache line holds pixels of two tiles, so those writes
// never contend for a line.
template <class T>
struct CacheAlignedAllocator {
  using value_type = T;
  CacheAlignedAllocator() = default;
  template <class U>
  CacheAlignedAllocator(const CacheAlignedAllocator<U>&) noexcept {}
  T* allocate(std::size_t n) { return static_cast<T*>(detail::allocate_buffer(n * sizeof(T))); }
  void deallocate(T* p, std::size_t) noexcept { detail::free_buffer(p); }
  template <class U>
  bool operator==(const CacheAlignedAllocator<U>&) const noexcept {
    return true;
  }
};

namespace detail {
// A clear that Renderer::clear recorded and no tile has applied yet (see Framebuffer).
struct PendingClear {
  bool color = false, depth = false;
  std::uint32_t color_value = 0;
  float depth_value = 1.0f;
};
inline constexpr int kTileBlocks = (kTileSize / 8) * (kTileSize / 8);  // 8x8 blocks of hierarchical depth per tile
struct TileMemory;
}  // namespace detail

class Renderer;

class Framebuffer {
 public:
  // Throws std::invalid_argument unless 1 <= width, height <= kMaxDimension and samples is 1, 2, 4 or 8.
  // With samples > 1 every pixel holds that many colour and depth samples at the standard Vulkan (and Direct3D)
  // sample positions while a frame is drawn, and color() is the average of each pixel's colour samples. The samples
  // themselves live in the memory of the tile being drawn and are not kept after the frame unless keep_samples(true)
  // asks for them.
  Framebuffer(int width, int height, int samples = 1);
  ~Framebuffer();
  // A move hands the pixels over; draws recorded for the source are drawn into it first.
  Framebuffer(Framebuffer&& other);
  Framebuffer& operator=(Framebuffer&& other);
  Framebuffer(const Framebuffer&) = delete;
  Framebuffer& operator=(const Framebuffer&) = delete;

  int width() const { return width_; }
  int height() const { return height_; }
  int samples() const { return samples_; }
  int tiles_x() const { return tiles_x_; }
  int tiles_y() const { return tiles_y_; }

  // Rows are top to bottom; x grows to the right. Valid after Renderer::finish(): with several samples, the
  // average of each pixel's samples (the resolve, which each tile does at the end of the frame).
  std::span<const std::uint32_t> color() const { return color_; }
  // color() for writing: draws recorded and not yet drawn are drawn first, and the caller may then store anything,
  // so the next clear rewrites every tile. With several samples and samples not kept, the next frame's draws start
  // from these colours in every sample; with samples kept, from the kept samples.
  std::span<std::uint32_t> mutable_color();
  // Multisampled targets only: whether each pixel's samples outlive the frame (sample_color, and frames drawn over
  // this one in several finish() calls without a clear between them, which then continue from every sample rather
  // than from the resolved colour and sample 0's depth). Off by default: the samples then cost tile memory only.
  // Turning it on keeps full-size planes of colour and depth per sample from the next frame on.
  void keep_samples(bool keep);
  bool keeps_samples() const { return keep_samples_; }
  // The colour of one sample of every pixel, not averaged, after finish(). With one sample, color(); with several,
  // keep_samples(true) must have been set before the frame (std::logic_error otherwise).
  std::span<const std::uint32_t> sample_color(int sample) const;
  // Whether the depth outlives the frame, for depth(), depth_at() and a next frame drawn without a depth clear. On
  // by default. Off, a frame's depth lives in the tile pass's memory only: a frame drawn in one tile pass never
  // writes the depth plane (a single 1920x1080 render touches 8 MB less fresh memory), one drawn in parts keeps it
  // between them, and finish() discards it: depth() and depth_at() then throw std::logic_error, and the next frame
  // starts from depth 1 unless it clears the depth itself.
  void keep_depth(bool keep) { keep_depth_ = keep; }
  bool keeps_depth() const { return keep_depth_; }
  // Depth of every pixel (sample 0's with several samples). Valid after Renderer::finish(), if kept.
  std::span<const float> depth() const {
    if (!keep_depth_) throw_depth_discarded();
    return depth_;
  }
  // depth() for writing: draws recorded and not yet drawn are drawn first; also voids the hierarchical depth bounds
  // (they become "unknown") and the kept clear.
  std::span<float> mutable_depth();
  std::uint32_t pixel(int x, int y) const { return color_[static_cast<std::size_t>(y) * width_ + x]; }
  float depth_at(int x, int y) const {
    if (!keep_depth_) throw_depth_discarded();
    return depth_[static_cast<std::size_t>(y) * width_ + x];
  }

  // The colour as bytes R, G, B, A per pixel, top row first (what PNG writers take).
  std::vector<std::uint8_t> rgba8() const;

 private:
  // Renderer::clear and finish record and apply clears, and the tile pass moves tiles in and out.
  friend class Renderer;

  // A clear is recorded and applied to each tile as the tile pass loads it into tile memory, or at
  // Renderer::finish() for tiles nothing touched. A tile that received the same colour and depth clear and
  // has not been written since (no draw touched it, no mutable_color() or mutable_depth() access) still holds it, and
  // is skipped: a model that covers part of the frame leaves the rest of the next frame's clear nothing to write.
  void request_clear(glm::vec4 color, float depth, bool clear_color = true, bool clear_depth = true);
  // Applies the pending clear to one tile if it has not been applied yet. Only the tile's owner thread calls it.
  void resolve_clear(int tile_index);
  // Applies the pending clear to every tile of one row of tiles that still needs it. When all of them do (the
  // common case at finish() after an empty or sparse frame), the row's pixels are contiguous in memory and are
  // filled in one pass, near memset speed; otherwise each run of neighbouring tiles that need it is filled one
  // pixel row at a time. Only the owner of that row of tiles calls it.
  void resolve_clear_tile_row(int tile_row);
  void resolve_all_clears();
  // Before the caller writes pixels itself: the draws recorded and the clears requested so far (a new
  // framebuffer's included) are applied first, so that they do not later overwrite what it writes.
  void settle_before_write();

  // For the renderer's tile pass, on the tile's owner thread: load_tile fills a thread's tile memory with the
  // tile's pending clear, or else its contents (every kept sample, or the resolved colour and depth in each
  // sample); store_tile writes the tile's final pixels back (the resolve with several samples, and kept samples).
  void load_tile(int tile_index, detail::TileMemory& memory);
  // store_depth false: the tile's depth is not written back (the last part of a frame whose depth is not kept).
  void store_tile(int tile_index, const detail::TileMemory& memory, bool store_depth = true);
  // At finish() of a frame whose depth is not kept, after its tiles are stored: the clears still pending then
  // apply to colour only (skip_pending_depth), and afterwards the depth is left pending as a clear to 1 in every
  // tile (discard_depth), so its plane is written only if someone reads it.
  void skip_pending_depth() { pending_.depth = false; }
  void discard_depth();
  [[noreturn]] static void throw_depth_discarded();

  // Hierarchical depth: one upper bound on the stored depth per 8x8 block; a triangle whose nearest point in a
  // block is behind the bound is rejected for the whole block without a per-pixel test. Each tile's kTileBlocks
  // bounds are contiguous (row-major over its 8x8 grid of blocks). Kept between frames with the depth they bound.
  static constexpr float kUnknownDepthBound = 3.402823466e+38f;
  std::size_t pixel_count() const { return static_cast<std::size_t>(width_) * height_; }
  std::size_t bounds_per_sample() const {
    return static_cast<std::size_t>(tiles_x_) * tiles_y_ * detail::kTileBlocks;
  }
  void reset_depth_bounds(int tile_index, float value);
  bool holds_samples() const { return !sample_color_.empty(); }
  // Allocates the sample planes (keep_samples without the settling): each sample takes the pixel's colour and depth.
  void hold_sample_planes();
  void detach_recorder();

  int width_, height_, samples_, tiles_x_, tiles_y_;
  // Left unset when made: a new framebuffer records a clear to colour 0 and depth 1 instead, which the first clear
  // asked for replaces, so its planes are written once, by that clear or by the draws, not twice.
  template <class T>
  using Plane = std::vector<T, detail::DefaultInitAllocator<CacheAlignedAllocator<T>>>;
  Plane<std::uint32_t> color_;  // the resolved colour with several samples
  Plane<float> depth_;          // sample 0's
  std::vector<float, CacheAlignedAllocator<float>> block_max_depth_;  // bounds of depth_
  // Kept samples (keep_samples): one whole image per sample (sample s at s * pixel_count()), with their bounds.
  Plane<std::uint32_t> sample_color_;
  Plane<float> sample_depth_;
  std::vector<float, CacheAlignedAllocator<float>> sample_bounds_;
  bool keep_samples_ = false;
  bool keep_depth_ = true;
  detail::PendingClear pending_;
  std::vector<std::uint8_t> tile_needs_clear_;
  // Per tile: it holds `held_` (a colour and depth clear) in every pixel. Tiles drawn into lose the mark.
  std::vector<std::uint8_t> tile_holds_clear_;
  detail::PendingClear held_;
  bool contents_exposed_ = false;  // writable color() or depth() since the last request_clear
  Renderer* recorder_ = nullptr;   // the renderer holding draws recorded for this target, not yet drawn
};

}  // namespace facet
