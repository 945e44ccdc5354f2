// renderer.cpp - the shader-independent half of a draw: painter's order, batched setup and binning, tile dispatch.
#include "facet/renderer.hpp"

#include <algorithm>
#include <numeric>
#include <thread>

#include "setup/setup.hpp"

namespace facet {
namespace {

int resolve_thread_count(int threads) {
  if (threads > 0) return threads;
  return static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

}  // namespace

Renderer::Renderer(int threads) : pool_(resolve_thread_count(threads)), scratch_(pool_.size()) {}

Renderer::~Renderer() = default;

void Renderer::clear(Framebuffer& target, glm::vec4 color, float depth) { target.request_clear(color, depth); }

void Renderer::finish(Framebuffer& target) {
  pool_.parallel_for(static_cast<std::size_t>(target.tiles_y()),
                     [&](std::size_t row, int) { target.resolve_clear_tile_row(static_cast<int>(row)); });
  target.resolve_all_clears();
}

void Renderer::execute(Framebuffer& target, const detail::DrawRequest& request) {
  using namespace detail;
  const bool triangles = request.kind == PrimitiveKind::triangles;
  const std::size_t per_primitive = triangles ? 3 : 2;
  const std::size_t count = request.indices.size() / per_primitive;
  const RenderState& state = *request.state;
  stats_ = {};
  stats_.primitives = count;

  const std::uint32_t* order = nullptr;
  if (triangles && state.order == DrawOrder::back_to_front) {
    sort_keys_.resize(count);
    setup_depth_keys(request.clip, request.vertex_count, request.indices, sort_keys_);
    // Farthest first; equal depths keep index order. A total order lets std::sort (which, unlike stable_sort,
    // needs no buffer) give the same result every time.
    order_.resize(count);
    std::iota(order_.begin(), order_.end(), 0u);
    std::sort(order_.begin(), order_.end(), [&](std::uint32_t a, std::uint32_t b) {
      return sort_keys_[a] != sort_keys_[b] ? sort_keys_[a] > sort_keys_[b] : a < b;
    });
    order = order_.data();
  }

  const std::size_t tiles = static_cast<std::size_t>(target.tiles_x()) * target.tiles_y();
  const std::size_t batch = kSetupChunk * kChunksPerBatch;
  for (std::size_t batch_first = 0; batch_first < count; batch_first += batch) {
    const std::size_t batch_count = std::min(batch, count - batch_first);
    const std::size_t chunk_count = (batch_count + kSetupChunk - 1) / kSetupChunk;
    if (chunks_.size() < chunk_count) chunks_.resize(chunk_count);

    pool_.parallel_for(chunk_count, [&](std::size_t c, int) {
      SetupChunk& chunk = chunks_[c];
      chunk.reset();
      const std::size_t first = batch_first + c * kSetupChunk;
      const SetupInput input{request.clip, request.clip_position, request.clip_source, request.projected, request.vertex_count, request.indices, order, first,
                             std::min(kSetupChunk, batch_first + batch_count - first), target.width(), target.height(),
                             target.tiles_x(), state.cull, state.line_width};
      if (triangles) setup_triangles(input, chunk);
      else setup_lines(input, chunk);
      chunk.sort_by_tile(tiles);
    });

    active_tiles_.clear();
    for (std::size_t t = 0; t < tiles; ++t)
      for (std::size_t c = 0; c < chunk_count; ++c)
        if (chunks_[c].has(t)) {
          active_tiles_.push_back(static_cast<int>(t));
          break;
        }
    for (std::size_t c = 0; c < chunk_count; ++c) {
      stats_.culled += chunks_[c].culled;
      stats_.clipped += chunks_[c].clipped;
      stats_.invalid += chunks_[c].invalid;
      stats_.binned += chunks_[c].triangles.size();
    }

    // One owner per tile: no two threads ever write the same pixel, so the tile loop needs no locks.
    pool_.parallel_for(active_tiles_.size(), [&](std::size_t i, int thread) {
      const int tile = active_tiles_[i];
      Framebuffer::PendingClear clear;
      if (request.deferred) clear = target.take_clear(tile);
      else target.resolve_clear(tile);
      const int x0 = (tile % target.tiles_x()) * kTileSize, y0 = (tile / target.tiles_x()) * kTileSize;
      const TileWork work{tile, x0, y0, std::min(x0 + kTileSize, target.width()),
                          std::min(y0 + kTileSize, target.height()), target.width(), target.color().data(),
                          target.depth_storage(), target.block_max_depth(), target.blocks_x(), chunks_.data(),
                          chunk_count, &scratch_[static_cast<std::size_t>(thread)], clear};
      request.raster(request.draw, work);
    });
  }
}

}  // namespace facet
