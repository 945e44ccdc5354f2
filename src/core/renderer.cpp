// renderer.cpp - the shader-independent half of a draw: painter's order, batched setup and binning, tile dispatch.
#include "facet/renderer.hpp"

#include <algorithm>
#include <numeric>
#include <thread>

#include <vector>

#include "core/thread_pool.hpp"
#include "facet/cpu_level.hpp"
#include "facet/detail/multisample.hpp"
#include "core/setup/setup.hpp"

namespace facet {
namespace {

int resolve_thread_count(int threads) {
  if (threads > 0) return threads;
  return static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

}  // namespace

struct Renderer::Work {
  explicit Work(int threads) : pool(threads), scratch(static_cast<std::size_t>(pool.size())) {}

  detail::VertexOutputs prepare_vertex_outputs(const detail::DrawRequest& request, std::size_t held, std::size_t first,
                                               int width, int height);
  detail::VertexRange batch_vertex_band(const detail::DrawRequest& request, std::size_t batch_first,
                                        std::size_t batch_count);
  void shade_vertex_range(const detail::DrawRequest& request, const detail::VertexOutputs& out, std::size_t begin,
                          std::size_t end, DrawStats& stats);

  detail::ThreadPool pool;
  // Post-transform vertices of the range being drawn (see VertexOutputs).
  std::vector<glm::vec4> clip;                     // clip positions, kept only for lines and the painter's sort
  std::vector<detail::ProjectedVertex> projected;  // the same after the divide, viewport and snapping
  std::vector<float> varyings;                     // varyings, float_count floats per vertex
  std::vector<detail::SetupChunk> chunks;
  std::vector<detail::VertexRange> chunk_bands;  // vertices each setup chunk of the batch references
  std::vector<std::uint32_t> order;              // painter's order
  std::vector<float> sort_keys;
  std::vector<std::uint64_t> active_tiles;   // tiles with work, most binned triangles first (see execute)
  std::vector<detail::TileScratch> scratch;  // per thread one per sample, for deferred shading
};

Renderer::Renderer(int threads) {
  detail::check_cpu_level_variable();
  work_ = std::make_unique<Work>(resolve_thread_count(threads));
}

Renderer::~Renderer() = default;

int Renderer::threads() const { return work_->pool.size(); }

void Renderer::parallel_for(std::size_t count, const std::function<void(std::size_t)>& body) {
  work_->pool.parallel_for(count, [&](std::size_t i, int) { body(i); });
}

void Renderer::clear(Framebuffer& target, glm::vec4 color, float depth) { target.request_clear(color, depth); }

void Renderer::finish(Framebuffer& target) {
  work_->pool.parallel_for(static_cast<std::size_t>(target.tiles_y()),
                           [&](std::size_t row, int) { target.resolve_clear_tile_row(static_cast<int>(row)); });
  target.resolve_all_clears();
}

detail::VertexOutputs Renderer::Work::prepare_vertex_outputs(const detail::DrawRequest& request, std::size_t held,
                                                             std::size_t first, int width, int height) {
  // Triangles need clip positions only to clip the few that cross the frustum, and recompute those (see
  // ClipPositionFn); lines and points clip every primitive and the painter's sort reads every depth, so those keep
  // them all.
  const bool triangles = request.kind == detail::PrimitiveKind::triangles;
  const bool keep_clip = !triangles || request.state->order == DrawOrder::back_to_front;
  if (keep_clip && clip.size() < held) clip.resize(held);
  if (triangles && projected.size() < held) projected.resize(held);
  if (varyings.size() < held * request.varying_floats) varyings.resize(held * request.varying_floats);
  return {first, keep_clip ? clip.data() : nullptr, triangles ? projected.data() : nullptr, varyings.data(), width,
          height};
}

// The vertices that a batch's primitives reference (empty if none is valid), from a scan per setup chunk.
detail::VertexRange Renderer::Work::batch_vertex_band(const detail::DrawRequest& request, std::size_t batch_first,
                                                      std::size_t batch_count) {
  using namespace detail;
  const std::size_t per_primitive = indices_per_primitive(request.kind);
  const std::size_t chunk_count = (batch_count + kSetupChunk - 1) / kSetupChunk;
  chunk_bands.resize(chunk_count);
  pool.parallel_for(chunk_count, [&](std::size_t c, int) {
    const std::size_t first = batch_first + c * kSetupChunk;
    chunk_bands[c] = setup_vertex_range(request.indices, per_primitive, request.vertex_count, first,
                                        std::min(kSetupChunk, batch_first + batch_count - first));
  });
  VertexRange band{request.vertex_count, 0};
  for (const VertexRange& b : chunk_bands)
    if (b.first < b.end) band = {std::min(band.first, b.first), std::max(band.end, b.end)};
  return band.first < band.end ? band : VertexRange{};
}

void Renderer::Work::shade_vertex_range(const detail::DrawRequest& request, const detail::VertexOutputs& out,
                                        std::size_t begin, std::size_t end, DrawStats& stats) {
  constexpr std::size_t kVertexChunk = 2048;
  stats.vertices_shaded += end - begin;
  pool.parallel_for((end - begin + kVertexChunk - 1) / kVertexChunk, [&](std::size_t chunk, int) {
    const std::size_t first = begin + chunk * kVertexChunk;
    request.shade_vertices(request.source, first, std::min(end, first + kVertexChunk), out);
  });
}

void Renderer::execute(Framebuffer& target, const detail::DrawRequest& request) {
  using namespace detail;
  Work& w = *work_;
  const bool triangles = request.kind == PrimitiveKind::triangles;
  const std::size_t per_primitive = indices_per_primitive(request.kind);
  const std::size_t count = request.indices.size() / per_primitive;
  const RenderState& state = *request.state;
  const bool painter = triangles && state.order == DrawOrder::back_to_front;
  stats_ = {};
  stats_.primitives = count;

  // Vertex stage. Meshes whose index order is coherent (grids, strips, any optimised mesh) reference a narrow band
  // of vertices per batch, so each batch shades just its band and post-transform memory follows the batch, not the
  // mesh. One batch, or bands that overlap too much (a shuffled index order), shade the draw's whole band once
  // instead: a mesh drawn in several parts (one per material) shades each part's vertices, not the whole array
  // each time. The painter's order shades every vertex (its sort reads them all first). Either way the
  // post-transform cache never misses: each vertex is shaded at most once per batch.
  // A draw's last part shorter than a batch joins the batch before it: one batch boundary fewer, i.e. one round of
  // barriers and one visit of the tiles both batches touch, for at most twice a batch's setup memory.
  const std::size_t batch = kSetupChunk * kChunksPerBatch;
  const auto batch_end = [&](std::size_t first) { return count - first < 2 * batch ? count : first + batch; };
  const std::size_t n = request.vertex_count;
  bool banded = !painter && batch_end(0) < count;
  VertexOutputs outputs{};
  const auto shade_band = [&](VertexRange band) {
    outputs = w.prepare_vertex_outputs(request, band.end - band.first, band.first, target.width(), target.height());
    stats_.vertices_held = std::max(stats_.vertices_held, band.end - band.first);
    w.shade_vertex_range(request, outputs, band.first, band.end, stats_);
  };
  if (!banded) shade_band(painter ? VertexRange{0, n} : w.batch_vertex_band(request, 0, count));

  const std::uint32_t* order = nullptr;
  if (painter) {
    w.sort_keys.resize(count);
    setup_depth_keys(outputs.clip, n, request.indices, w.sort_keys);
    // Farthest first; equal depths keep index order. A total order lets std::sort (which, unlike stable_sort,
    // needs no buffer) give the same result every time.
    w.order.resize(count);
    std::iota(w.order.begin(), w.order.end(), 0u);
    std::sort(w.order.begin(), w.order.end(), [&](std::uint32_t a, std::uint32_t b) {
      return w.sort_keys[a] != w.sort_keys[b] ? w.sort_keys[a] > w.sort_keys[b] : a < b;
    });
    order = w.order.data();
  }

  const std::size_t tiles = static_cast<std::size_t>(target.tiles_x()) * target.tiles_y();
  const int samples = target.samples();
  const std::size_t scratch_needed = static_cast<std::size_t>(w.pool.size()) * static_cast<std::size_t>(samples);
  if (w.scratch.size() < scratch_needed) w.scratch.resize(scratch_needed);
  for (std::size_t batch_first = 0, next_batch = 0; batch_first < count; batch_first = next_batch) {
    next_batch = batch_end(batch_first);
    const std::size_t batch_count = next_batch - batch_first;
    const std::size_t chunk_size = setup_chunk_size(batch_count);
    const std::size_t chunk_count = (batch_count + chunk_size - 1) / chunk_size;
    if (w.chunks.size() < chunk_count) w.chunks.resize(chunk_count);
    if (banded) {
      const VertexRange band = w.batch_vertex_band(request, batch_first, batch_count);
      // Shading shared vertices again at batch boundaries is cheap; shading the mesh several times over is not. A
      // band of most of the mesh is a sign of an incoherent order: the whole span, once, costs little more.
      const std::size_t width = band.end - band.first;
      banded = width <= n / 4 * 3 && stats_.vertices_shaded + width <= n + n / 4;
      shade_band(banded ? band : VertexRange{0, n});
    }

    w.pool.parallel_for(chunk_count, [&](std::size_t c, int) {
      SetupChunk& chunk = w.chunks[c];
      chunk.reset();
      const std::size_t first = batch_first + c * chunk_size;
      const SetupInput input{.clip = outputs.clip,
                             .projected = outputs.projected,
                             .vertex_first = outputs.first,
                             .clip_position = request.clip_position,
                             .clip_source = request.source,
                             .vertex_count = request.vertex_count,
                             .indices = request.indices,
                             .order = order,
                             .first = first,
                             .count = std::min(chunk_size, batch_first + batch_count - first),
                             .width = target.width(),
                             .height = target.height(),
                             .tiles_x = target.tiles_x(),
                             .cull = state.cull,
                             .line_width = state.line_width,
                             .samples = samples,
                             .point_size = state.point_size,
                             .point_shape = state.point_shape};
      if (triangles) setup_triangles(input, chunk);
      else if (request.kind == PrimitiveKind::lines) setup_lines(input, chunk);
      else setup_points(input, chunk);
      chunk.sort_by_tile(tiles);
    });
    // Heaviest tiles first, by binned triangles: the pool hands tiles out in this order, so the last ones to start
    // are short and the threads finish together (in row order the centre of a model came last and one thread ran
    // on alone: sphere:224 and 707 1.5-3% slower). Each key is the inverted count above the tile index, a total
    // order, so std::sort needs no buffer and the order is the same every frame.
    w.active_tiles.clear();
    for (std::size_t t = 0; t < tiles; ++t) {
      std::uint32_t binned = 0;
      for (std::size_t c = 0; c < chunk_count; ++c) binned += w.chunks[c].binned_count(t);
      if (binned) w.active_tiles.push_back(std::uint64_t{~binned} << 32 | t);
    }
    std::sort(w.active_tiles.begin(), w.active_tiles.end());
    for (std::size_t c = 0; c < chunk_count; ++c) {
      stats_.culled += w.chunks[c].culled;
      stats_.clipped += w.chunks[c].clipped;
      stats_.invalid += w.chunks[c].invalid;
      stats_.binned += w.chunks[c].triangles.size();
    }

    // One owner per tile: no two threads ever write the same pixel, so the tile loop needs no locks.
    w.pool.parallel_for(w.active_tiles.size(), [&](std::size_t i, int thread) {
      const int tile = static_cast<int>(w.active_tiles[i] & 0xffffffffu);
      const detail::PendingClear clear = target.begin_tile_draw(tile, request.deferred);
      const int x0 = (tile % target.tiles_x()) * kTileSize, y0 = (tile / target.tiles_x()) * kTileSize;
      const TileWork work{.tile = tile,
                          .x0 = x0,
                          .y0 = y0,
                          .x1 = std::min(x0 + kTileSize, target.width()),
                          .y1 = std::min(y0 + kTileSize, target.height()),
                          .stride = target.width(),
                          .color = target.color_storage(),
                          .depth = target.depth_storage(),
                          .depth_bounds = target.tile_depth_bounds(tile),
                          .chunks = w.chunks.data(),
                          .chunk_count = chunk_count,
                          .varyings = outputs.varyings,
                          .scratch = &w.scratch[static_cast<std::size_t>(thread) * static_cast<std::size_t>(samples)],
                          .clear = clear,
                          .last_batch = next_batch == count,
                          .samples = samples,
                          .sample_stride = target.sample_offset(1),
                          .bounds_stride = target.bounds_per_sample(),
                          .resolved = target.resolved_storage()};
      request.raster(request.draw, work);
    });
  }
}

}  // namespace facet
