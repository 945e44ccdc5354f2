// renderer.cpp - the shader-independent half of a frame: painter's order, batched setup and binning, the tile pass.
#include "facet/renderer.hpp"

#include <algorithm>
#include <limits>
#include <memory>
#include <numeric>
#include <thread>
#include <utility>
#include <vector>

#include "core/thread_pool.hpp"
#include "facet/cpu_level.hpp"
#include "facet/detail/bits.hpp"
#include "facet/detail/multisample.hpp"
#include "facet/detail/tile_memory.hpp"
#include "core/setup/setup.hpp"

namespace facet {
namespace {

int resolve_thread_count(int threads) {
  if (threads > 0) return threads;
  return static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

}  // namespace

// A frame's draws are recorded, not drawn: each batch of a draw is set up and binned as it comes, and keeps its
// varyings, set-up primitives and bins until the frame's tile pass (flush_recorded), which rasterizes every tile
// once with all the batches that touch it, in the order they were drawn, in the thread's tile memory.
// Recorded work is bounded (see part_limit in execute): past the bound, the work recorded so far is drawn before the
// next batch is set up, and a multisampled target then keeps full-size sample planes so that the rest of the frame
// continues from them.
struct Renderer::Work {
  explicit Work(int threads)
      : pool(threads),
        scratch(static_cast<std::size_t>(pool.size())),
        memory(static_cast<std::size_t>(pool.size())),
        tile_sorts(static_cast<std::size_t>(pool.size())) {}

  detail::VertexOutputs prepare_vertex_outputs(const detail::DrawRequest& request, std::size_t held, std::size_t first,
                                               int width, int height);
  detail::VertexRange batch_vertex_band(const detail::DrawRequest& request, std::size_t batch_first,
                                        std::size_t batch_count);
  void shade_vertex_range(const detail::DrawRequest& request, const detail::VertexOutputs& out, std::size_t begin,
                          std::size_t end, DrawStats& stats);
  std::size_t new_varying_block(std::size_t floats);

  // One batch of a recorded draw, set up and binned: what the tile pass needs to rasterize it.
  struct Batch {
    std::vector<detail::SetupChunk> chunks;  // kept from frame to frame for their memory
    std::size_t chunk_count = 0;
    std::size_t varyings = 0;  // its block of varying_blocks
    detail::TileRasterFn raster = nullptr;
    const void* draw = nullptr;  // the draw's copies of its shader and state, in `copies`
    // Drawn farthest first, sorted per tile: the block of varying_blocks holding each primitive's depth key.
    std::size_t keys = kUnsorted;
  };
  static constexpr std::size_t kUnsorted = ~std::size_t{0};
  // A tile's triangle of a run of sorted batches: compared by its depth key mapped to an unsigned integer and
  // inverted (farthest first), then by its batch's place in the run, its primitive and its reference.
  struct SortEntry {
    std::uint32_t depth, batch, primitive, ref;
    bool operator<(const SortEntry& o) const {
      if (depth != o.depth) return depth < o.depth;
      if (batch != o.batch) return batch < o.batch;
      return primitive != o.primitive ? primitive < o.primitive : ref < o.ref;
    }
  };
  struct TileSort {
    std::vector<SortEntry> entries;
    std::vector<std::uint32_t> refs;  // the entries' references, in their order
  };
  void sort_tile(const std::uint32_t* run, std::size_t run_size, std::uint32_t tile, TileSort& sort) const;
  // The recorded draws' copies of their shaders and states: blocks that stay from frame to frame, so that steady
  // frames do not touch the heap, and the destructors to run when the frame is drawn.
  struct Copies {
    static constexpr std::size_t kBlock = 16 << 10;
    struct Block {
      std::unique_ptr<std::byte[], void (*)(std::byte*)> bytes{nullptr, nullptr};
      std::size_t size = 0;
    };
    std::vector<Block> blocks;
    std::size_t block = 0, used = 0;
    std::vector<std::pair<void*, void (*)(void*)>> destructors;

    void* allocate(std::size_t bytes);
    void clear();
  };
  using VaryingBlock = std::vector<float, detail::DefaultInitAllocator<CacheAlignedAllocator<float>>>;

  detail::ThreadPool pool;
  // Post-transform vertices of the range being set up (see VertexOutputs); the varyings live in varying_blocks.
  std::vector<glm::vec4> clip;                     // clip positions, kept only for lines and the painter's sort
  std::vector<detail::ProjectedVertex> projected;  // the same after the divide, viewport and snapping
  std::vector<detail::VertexRange> chunk_bands;    // vertices each setup chunk of the batch references
  std::vector<std::uint32_t> order;                // painter's order
  std::vector<float> sort_keys;

  // The frame being recorded: its target, batches and varyings (both pools only grow, and are reused), the
  // (tile, batch) pairs with work in batch order, and per tile its primitives binned so far.
  Framebuffer* target = nullptr;
  std::vector<Batch> batches;
  std::size_t batch_count = 0;
  std::vector<VaryingBlock> varying_blocks;
  std::size_t varying_block_count = 0;
  std::size_t current_block = 0;  // the varyings that the draw being recorded sets up from
  std::size_t recorded_bytes = 0;
  std::size_t recorded_limit = kDefaultRecordedBytes;
  std::vector<std::uint32_t> pair_tile, pair_batch;
  std::vector<std::uint32_t> tile_load;
  Copies copies;

  // The tile pass's: per-tile lists of batches, tiles with work (most binned primitives first), and per thread its
  // tile memory and one deferred-shading scratch per sample.
  std::vector<std::uint32_t> tile_first, tile_batches;
  std::vector<std::uint64_t> active_tiles;
  std::vector<detail::TileScratch> scratch;
  std::vector<detail::TileMemory> memory;
  std::vector<TileSort> tile_sorts;  // per thread
};

Renderer::Renderer(int threads) {
  detail::check_cpu_level_variable();
  work_ = std::make_unique<Work>(resolve_thread_count(threads));
}

Renderer::~Renderer() { drop_recorded(); }

int Renderer::threads() const { return work_->pool.size(); }

void Renderer::set_recorded_bytes_limit(std::size_t bytes) { work_->recorded_limit = bytes; }

std::size_t Renderer::recorded_bytes_limit() const { return work_->recorded_limit; }

void Renderer::parallel_for(std::size_t count, const std::function<void(std::size_t)>& body) {
  work_->pool.parallel_for(count, [&](std::size_t i, int) { body(i); });
}

void* Renderer::Work::Copies::allocate(std::size_t bytes) {
  bytes = (bytes + kRecordAlign - 1) / kRecordAlign * kRecordAlign;
  while (block < blocks.size() && used + bytes > blocks[block].size) ++block, used = 0;
  if (block == blocks.size()) {
    const std::size_t size = std::max(kBlock, bytes);
    auto* memory = static_cast<std::byte*>(::operator new(size, std::align_val_t{kRecordAlign}));
    blocks.push_back({{memory, [](std::byte* p) { ::operator delete(p, std::align_val_t{kRecordAlign}); }}, size});
    used = 0;
  }
  void* at = blocks[block].bytes.get() + used;
  used += bytes;
  return at;
}

void Renderer::Work::Copies::clear() {
  for (auto it = destructors.rbegin(); it != destructors.rend(); ++it) it->second(it->first);
  destructors.clear();
  block = used = 0;
}

void* Renderer::record_storage(Framebuffer& target, std::size_t bytes) {
  Work& w = *work_;
  if (w.target != &target) {
    flush_recorded();
    w.target = &target;
    target.recorder_ = this;
  }
  return w.copies.allocate(bytes);
}

void Renderer::record_destructor(void* object, void (*destroy)(void*)) {
  work_->copies.destructors.emplace_back(object, destroy);
}

void Renderer::clear(Framebuffer& target, glm::vec4 color, float depth) {
  if (work_->target == &target) flush_recorded();
  target.request_clear(color, depth);
}

void Renderer::finish(Framebuffer& target) {
  // A depth not kept is not stored by the frame's last tile pass, nor cleared in the tiles no draw touched.
  const bool discard = !target.keeps_depth();
  flush_recorded(!(discard && work_->target == &target));
  if (discard) target.skip_pending_depth();
  work_->pool.parallel_for(static_cast<std::size_t>(target.tiles_y()),
                           [&](std::size_t row, int) { target.resolve_clear_tile_row(static_cast<int>(row)); });
  target.resolve_all_clears();
  if (discard) target.discard_depth();
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
  current_block = new_varying_block(held * request.varying_floats);
  return {first, keep_clip ? clip.data() : nullptr, triangles ? projected.data() : nullptr,
          varying_blocks[current_block].data(), width, height};
}

std::size_t Renderer::Work::new_varying_block(std::size_t floats) {
  if (varying_block_count == varying_blocks.size()) varying_blocks.emplace_back();
  VaryingBlock& block = varying_blocks[varying_block_count];
  if (block.size() < floats) {
    block.clear();  // nothing to copy when it grows
    block.resize(floats);
  }
  recorded_bytes += floats * sizeof(float);
  return varying_block_count++;
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
  // The painter's order is sorted per tile, in the tile pass, by each primitive's depth key (ties in index order),
  // on every thread: the tile's triangles in the order a sort of the whole draw gives them, without that sort,
  // which ran on one thread before setup. It needs the draw in one batch (the sort spans all its triangles); a draw
  // of more chunks than a batch can reference (16.7 million triangles) is sorted whole instead.
  const bool sort_per_tile =
      painter && (count + setup_chunk_size(count) - 1) / setup_chunk_size(count) <= kMaxChunksPerBatch;
  stats_ = {};
  stats_.primitives = count;

  // Vertex stage. Meshes whose index order is coherent (grids, strips, any optimised mesh) reference a narrow band
  // of vertices per batch, so each batch shades just its band, which it records with its varyings (the positions
  // that setup reads are reused from batch to batch). One batch, or bands that overlap too much (a shuffled index
  // order), shade the draw's whole band once instead: a mesh drawn in several parts (one per material) shades each
  // part's vertices, not the whole array each time. The painter's order shades every vertex (its sort reads them
  // all first). Either way the post-transform cache never misses: each vertex is shaded at most once per batch.
  // A draw's last part shorter than a batch joins the batch before it: one batch boundary fewer, i.e. one round of
  // barriers, for at most twice a batch's setup memory at a time.
  const std::size_t batch = kSetupChunk * kChunksPerBatch;
  const auto batch_end = [&](std::size_t first) {
    return sort_per_tile || count - first < 2 * batch ? count : first + batch;
  };
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
  if (painter && !sort_per_tile) {
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
  const auto part_limit = [&] {
    // Draws in the painter's order that follow each other are composited together per tile, which needs them in
    // one part: only the limit itself cuts them.
    if (sort_per_tile && w.batch_count > 0 && w.batches[w.batch_count - 1].keys != Work::kUnsorted)
      return w.recorded_limit;
    // Once the target has every plane a part continues from (always with one sample), parts cost only their tiles'
    // loads and stores, and cache-sized ones read their set-up work back from the cache: sphere:707 at 1 sample,
    // 2 threads, 17.3 ms a frame in parts of 2 MiB against 20.8 ms in one tile pass (medians of 5 alternated
    // rounds). A multisampled target without sample planes records its whole frame up to the limit, unless the
    // frame would outweigh the planes (below): holding them costs fresh memory (66 MB for 4 samples at 1920x1080).
    if (samples == 1 || target.holds_samples()) return std::min(w.recorded_limit, kCachedRecordedBytes);
    return w.recorded_limit;
  };
  // A multisampled frame whose recorded work would outweigh its sample planes takes the planes now and goes on in
  // cache-sized parts, rather than recording its set-up work whole: a million-point cloud at 4 samples and
  // 1920x1080 records 190 MB, where the planes weigh 66 MB and are touched only where parts store tiles
  // (hold_sample_planes). Each primitive records at most one set-up triangle but for clipped, line and disc
  // primitives; a draw that culls back faces is taken to record half of them. Small targets keep recording: their
  // planes save little, and each part loads and stores most of their few tiles (an 870k-triangle thumbnail of
  // 256x256 took 200 ms in parts against 145 ms recorded whole).
  constexpr std::size_t kLeastPlanesBytes = std::size_t{16} << 20;
  if (samples > 1 && !target.holds_samples() && !sort_per_tile) {
    const std::size_t planes = target.pixel_count() * static_cast<std::size_t>(samples) *
                               (sizeof(std::uint32_t) + sizeof(float));
    const std::size_t recording = count * sizeof(TriangleSetup) / (state.cull == CullMode::none ? 1 : 2);
    if (planes >= kLeastPlanesBytes && w.recorded_bytes + recording > planes) target.hold_sample_planes();
  }
  for (std::size_t batch_first = 0, next_batch = 0; batch_first < count; batch_first = next_batch) {
    next_batch = batch_end(batch_first);
    const std::size_t batch_count = next_batch - batch_first;
    const std::size_t chunk_size = setup_chunk_size(batch_count);
    const std::size_t chunk_count = (batch_count + chunk_size - 1) / chunk_size;
    if (w.recorded_bytes > part_limit() && w.batch_count > 0) {
      // Too much recorded: draw it now, and go on recording the frame (the draws' copies stay). A whole-draw block
      // of varyings is still needed by this draw's later batches; a banded draw shades a new one below.
      if (samples > 1) target.hold_sample_planes();
      draw_recorded_tiles(true);
      const std::size_t kept = w.current_block;
      release_batches();
      if (!banded) {
        std::swap(w.varying_blocks[0], w.varying_blocks[kept]);
        w.varying_block_count = 1;
        w.current_block = 0;
        w.recorded_bytes = w.varying_blocks[0].size() * sizeof(float);
      }
    }
    if (banded) {
      const VertexRange band = w.batch_vertex_band(request, batch_first, batch_count);
      // Shading shared vertices again at batch boundaries is cheap; shading the mesh several times over is not. A
      // band of most of the mesh is a sign of an incoherent order: the whole span, once, costs little more.
      const std::size_t width = band.end - band.first;
      banded = width <= n / 4 * 3 && stats_.vertices_shaded + width <= n + n / 4;
      shade_band(banded ? band : VertexRange{0, n});
    }
    if (w.batch_count == 0) w.tile_load.assign(tiles, 0);  // the frame's first batch, or the first after a part

    std::size_t keys = Work::kUnsorted;
    if (sort_per_tile) {
      keys = w.new_varying_block(count);
      setup_depth_keys(outputs.clip, n, request.indices,
                       std::span<float>(w.varying_blocks[keys].data(), count));
    }
    if (w.batch_count == w.batches.size()) w.batches.emplace_back();
    Work::Batch& recorded = w.batches[w.batch_count++];
    if (recorded.chunks.size() < chunk_count) recorded.chunks.resize(chunk_count);
    recorded.chunk_count = chunk_count;
    recorded.varyings = w.current_block;
    recorded.raster = request.raster;
    recorded.draw = request.draw;
    recorded.keys = keys;
    w.pool.parallel_for(chunk_count, [&](std::size_t c, int) {
      SetupChunk& chunk = recorded.chunks[c];
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
                             .point_shape = state.point_shape,
                             .point_size_per_w = state.point_size_per_w};
      if (triangles) setup_triangles(input, chunk);
      else if (request.kind == PrimitiveKind::lines) setup_lines(input, chunk);
      else setup_points(input, chunk);
      chunk.sort_by_tile(tiles);
    });
    const auto batch_index = static_cast<std::uint32_t>(w.batch_count - 1);
    for (std::size_t t = 0; t < tiles; ++t) {
      std::uint32_t binned = 0;
      for (std::size_t c = 0; c < chunk_count; ++c) binned += recorded.chunks[c].binned_count(t);
      if (!binned) continue;
      w.pair_tile.push_back(static_cast<std::uint32_t>(t));
      w.pair_batch.push_back(batch_index);
      w.tile_load[t] += binned;
    }
    for (std::size_t c = 0; c < chunk_count; ++c) {
      const SetupChunk& chunk = recorded.chunks[c];
      stats_.culled += chunk.culled;
      stats_.clipped += chunk.clipped;
      stats_.invalid += chunk.invalid;
      stats_.binned += chunk.triangles.size();
      w.recorded_bytes +=
          chunk.triangles.size() * sizeof(TriangleSetup) + chunk.binned.size() * sizeof(std::uint32_t);
    }
  }
}

void Renderer::flush_recorded(bool store_depth) {
  if (!work_->target) return;
  draw_recorded_tiles(store_depth);
  drop_recorded();
}

void Renderer::draw_recorded_tiles(bool store_depth) {
  using namespace detail;
  Work& w = *work_;
  Framebuffer* const target = w.target;
  const std::size_t tiles = w.tile_load.size();
  const int samples = target->samples();

  // Each tile's batches, in the order they were recorded (a counting sort of the pairs by tile).
  w.tile_first.assign(tiles + 1, 0);
  for (const std::uint32_t t : w.pair_tile) ++w.tile_first[t + 1];
  for (std::size_t t = 0; t < tiles; ++t) w.tile_first[t + 1] += w.tile_first[t];
  w.tile_batches.resize(w.pair_tile.size());
  for (std::size_t i = 0; i < w.pair_tile.size(); ++i)
    w.tile_batches[w.tile_first[w.pair_tile[i]]++] = w.pair_batch[i];
  for (std::size_t t = tiles; t > 0; --t) w.tile_first[t] = w.tile_first[t - 1];
  w.tile_first[0] = 0;
  // Heaviest tiles first, by binned primitives: the pool hands tiles out in this order, so the last ones to start
  // are short and the threads finish together (in row order the centre of a model came last and one thread ran
  // on alone: sphere:224 and 707 1.5-3% slower). Each key is the inverted count above the tile index, a total
  // order, so std::sort needs no buffer and the order is the same every frame.
  w.active_tiles.clear();
  for (std::size_t t = 0; t < tiles; ++t)
    if (w.tile_load[t]) w.active_tiles.push_back(std::uint64_t{~w.tile_load[t]} << 32 | t);
  std::sort(w.active_tiles.begin(), w.active_tiles.end());

  // A tile's sort holds at most its binned primitives: room for the heaviest tile's, and half again, reserved here
  // so that steady frames, whose tiles go to threads in no fixed way, do not grow them.
  const bool any_sorted = std::any_of(w.batches.begin(), w.batches.begin() + static_cast<std::ptrdiff_t>(w.batch_count),
                                      [](const Work::Batch& b) { return b.keys != Work::kUnsorted; });
  if (any_sorted && !w.active_tiles.empty()) {
    const std::size_t heaviest = ~(w.active_tiles.front() >> 32) & 0xffffffffu;
    for (Work::TileSort& sort : w.tile_sorts)
      if (sort.entries.capacity() < heaviest) {
        sort.entries.reserve(heaviest + heaviest / 2);
        sort.refs.reserve(heaviest + heaviest / 2);
      }
  }
  const std::size_t scratch_needed = static_cast<std::size_t>(w.pool.size()) * static_cast<std::size_t>(samples);
  if (w.scratch.size() < scratch_needed) w.scratch.resize(scratch_needed);
  // One owner per tile: no two threads ever write the same pixel, so the tile pass needs no locks.
  w.pool.parallel_for(w.active_tiles.size(), [&](std::size_t i, int thread) {
    const int tile = static_cast<int>(w.active_tiles[i] & 0xffffffffu);
    TileMemory& memory = w.memory[static_cast<std::size_t>(thread)];
    target->load_tile(tile, memory);
    const int x0 = (tile % target->tiles_x()) * kTileSize, y0 = (tile / target->tiles_x()) * kTileSize;
    const auto raster = [&](const Work::Batch& batch, const std::uint32_t* sorted, std::size_t sorted_count) {
      const TileWork work{.tile = tile,
                          .x0 = x0,
                          .y0 = y0,
                          .x1 = std::min(x0 + kTileSize, target->width()),
                          .y1 = std::min(y0 + kTileSize, target->height()),
                          .stride = kTileSize,
                          .color = memory.color_of(0),
                          .depth = memory.depth_of(0),
                          .depth_bounds = memory.bounds_of(0),
                          .chunks = batch.chunks.data(),
                          .chunk_count = batch.chunk_count,
                          .sorted = sorted,
                          .sorted_count = sorted_count,
                          .varyings = w.varying_blocks[batch.varyings].data(),
                          .scratch = &w.scratch[static_cast<std::size_t>(thread) * static_cast<std::size_t>(samples)],
                          .lazy_clear = &memory.lazy_clear,
                          .samples = samples,
                          .sample_stride = TileMemory::kPixels,
                          .bounds_stride = kTileBlocks};
      batch.raster(batch.draw, work);
    };
    const std::uint32_t* const listed = w.tile_batches.data();
    for (std::uint32_t k = w.tile_first[tile], last = w.tile_first[tile + 1]; k < last;) {
      if (w.batches[listed[k]].keys == Work::kUnsorted) {
        raster(w.batches[listed[k++]], nullptr, 0);
        continue;
      }
      // Consecutive batches in the painter's order are composited together: their triangles that touch the tile,
      // farthest first across all of them, each stretch of one batch's triangles rasterized with its shader.
      std::uint32_t end = k + 1;
      while (end < last && w.batches[listed[end]].keys != Work::kUnsorted) ++end;
      Work::TileSort& sort = w.tile_sorts[static_cast<std::size_t>(thread)];
      w.sort_tile(listed + k, end - k, static_cast<std::uint32_t>(tile), sort);
      for (std::size_t first = 0, stretch = 0; first < sort.entries.size(); first = stretch) {
        const std::uint32_t batch = sort.entries[first].batch;
        for (stretch = first + 1; stretch < sort.entries.size() && sort.entries[stretch].batch == batch;) ++stretch;
        raster(w.batches[listed[k + batch]], sort.refs.data() + first, stretch - first);
      }
      k = end;
    }
    target->store_tile(tile, memory, store_depth);
  });
}

// The tile's triangles of a run of batches drawn farthest first (run lists them by index in `batches`), in the
// order of a sort of all of them by (depth key descending, batch, primitive). For one draw that is the order a sort
// of the whole draw gives, restricted to the tile; a clipped primitive's pieces keep the order they were set up in
// (their references ascend). Keys map to unsigned integers of the same order (-0 as +0).
void Renderer::Work::sort_tile(const std::uint32_t* run, std::size_t run_size, std::uint32_t tile,
                               TileSort& sort) const {
  sort.entries.clear();
  for (std::size_t b = 0; b < run_size; ++b) {
    const Batch& batch = batches[run[b]];
    const float* keys = varying_blocks[batch.keys].data();
    for (std::size_t c = 0; c < batch.chunk_count; ++c) {
      const detail::SetupChunk& chunk = batch.chunks[c];
      for (std::uint32_t i = chunk.first[tile]; i < chunk.first[tile + 1]; ++i) {
        const std::uint32_t index = chunk.binned[i];
        const std::uint32_t primitive = chunk.triangles[index].primitive;
        const auto bits = detail::bit_cast<std::uint32_t>(keys[primitive] + 0.0f);
        const std::uint32_t ordered = bits & 0x80000000u ? ~bits : bits | 0x80000000u;
        sort.entries.push_back({~ordered, static_cast<std::uint32_t>(b), primitive, detail::triangle_ref(c, index)});
      }
    }
  }
  std::sort(sort.entries.begin(), sort.entries.end());
  sort.refs.resize(sort.entries.size());
  for (std::size_t k = 0; k < sort.entries.size(); ++k) sort.refs[k] = sort.entries[k].ref;
}

void Renderer::release_batches() {
  Work& w = *work_;
  w.batch_count = 0;
  w.varying_block_count = 0;
  w.recorded_bytes = 0;
  w.pair_tile.clear();
  w.pair_batch.clear();
}

void Renderer::drop_recorded() {
  Work& w = *work_;
  if (w.target) w.target->recorder_ = nullptr;
  w.target = nullptr;
  release_batches();
  w.copies.clear();
}

}  // namespace facet
