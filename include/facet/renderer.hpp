// renderer.hpp - the pipeline front door: clear, draw triangles or lines with a Shader, finish.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "facet/framebuffer.hpp"
#include "facet/render_state.hpp"
#include "facet/shader.hpp"
#include "facet/detail/binning.hpp"
#include "facet/detail/thread_pool.hpp"
#include "facet/detail/triangle_setup.hpp"

namespace facet {

// Counters of the last draw, for tests and tuning.
struct DrawStats {
  std::size_t primitives = 0;  // submitted
  std::size_t culled = 0;      // back/front-face or zero area
  std::size_t clipped = 0;     // crossed a frustum plane and were split
  std::size_t invalid = 0;     // referenced a vertex outside the vertex span; skipped
  std::size_t binned = 0;      // set-up triangles that reached rasterization
};

namespace detail {
enum class PrimitiveKind { triangles, lines };
using TileRasterFn = void (*)(const void* draw, const TileWork& work);
// A draw's shader and vertices, for recomputing clip positions the vertex stage did not keep.
template <Shader S>
struct VertexSource {
  const S* shader;
  const typename S::Vertex* vertices;
  static glm::vec4 clip_position(const void* source, std::uint32_t vertex) {
    const auto& self = *static_cast<const VertexSource*>(source);
    return self.shader->vertex(self.vertices[vertex]).clip;
  }
};

struct DrawRequest {
  PrimitiveKind kind;
  const glm::vec4* clip;  // every vertex's clip position, or nullptr: ask clip_position
  ClipPositionFn clip_position;
  const void* clip_source;
  const ProjectedVertex* projected;
  std::size_t vertex_count;
  std::span<const std::uint32_t> indices;
  const RenderState* state;
  TileRasterFn raster;
  const void* draw;  // what `raster` reads: shader, varyings and state
  bool deferred;     // tiles keep their depth locally (see raster_deferred.hpp)
};
}  // namespace detail

class Renderer {
 public:
  // threads = 0 uses every hardware thread; the calling thread is one of them.
  explicit Renderer(int threads = 0);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  int threads() const { return pool_.size(); }

  // Records a clear; each tile applies it the first time it is drawn (while hot in cache) or at finish().
  void clear(Framebuffer& target, glm::vec4 color = {0, 0, 0, 1}, float depth = 1.0f);

  // Draws indexed triangles (3 indices each, counter-clockwise front faces). Indices outside the vertex span skip
  // their triangle. Returns when the pixels are in `target`.
  template <Shader S>
  void draw(Framebuffer& target, const S& shader, std::span<const typename S::Vertex> vertices,
            std::span<const std::uint32_t> indices, const RenderState& state = {});

  // Draws indexed line segments (2 indices each), state.line_width pixels wide, never culled.
  template <Shader S>
  void draw_lines(Framebuffer& target, const S& shader, std::span<const typename S::Vertex> vertices,
                  std::span<const std::uint32_t> indices, const RenderState& state = {});

  // Applies clears no draw has touched. Call before reading the framebuffer.
  void finish(Framebuffer& target);

  const DrawStats& last_stats() const { return stats_; }

 private:
  template <Shader S>
  void draw_primitives(detail::PrimitiveKind kind, Framebuffer& target, const S& shader,
                       std::span<const typename S::Vertex> vertices, std::span<const std::uint32_t> indices,
                       const RenderState& state);
  void execute(Framebuffer& target, const detail::DrawRequest& request);

  detail::ThreadPool pool_;
  std::vector<glm::vec4> clip_;     // post-transform positions, kept only for lines and the painter's sort
  std::vector<detail::ProjectedVertex> projected_;  // the same after the divide, viewport and snapping
  std::vector<float> varyings_;     // post-transform varyings, float_count floats per vertex
  std::vector<detail::SetupChunk> chunks_;
  std::vector<std::uint32_t> order_;  // painter's order
  std::vector<float> sort_keys_;
  std::vector<int> active_tiles_;
  std::vector<detail::TileScratch> scratch_;  // one per thread, for deferred shading
  DrawStats stats_;
};

}  // namespace facet

#include "facet/detail/raster_tile.hpp"

namespace facet {

template <Shader S>
void Renderer::draw(Framebuffer& target, const S& shader, std::span<const typename S::Vertex> vertices,
                    std::span<const std::uint32_t> indices, const RenderState& state) {
  draw_primitives(detail::PrimitiveKind::triangles, target, shader, vertices, indices, state);
}

template <Shader S>
void Renderer::draw_lines(Framebuffer& target, const S& shader, std::span<const typename S::Vertex> vertices,
                          std::span<const std::uint32_t> indices, const RenderState& state) {
  draw_primitives(detail::PrimitiveKind::lines, target, shader, vertices, indices, state);
}

template <Shader S>
void Renderer::draw_primitives(detail::PrimitiveKind kind, Framebuffer& target, const S& shader,
                               std::span<const typename S::Vertex> vertices, std::span<const std::uint32_t> indices,
                               const RenderState& state) {
  using Varyings = typename S::Varyings;
  constexpr std::size_t floats = float_count_v<Varyings>;
  const std::size_t n = vertices.size();
  // Triangles need clip positions only to clip the few that cross the frustum, and recompute them for those (see
  // VertexSource); lines clip every segment and the painter's sort reads every depth, so those keep them all.
  const bool project = kind == detail::PrimitiveKind::triangles;
  const bool keep_clip = !project || state.order == DrawOrder::back_to_front;
  if (keep_clip && clip_.size() < n) clip_.resize(n);
  if (project && projected_.size() < n) projected_.resize(n);
  if (varyings_.size() < n * floats) varyings_.resize(n * floats);

  // Vertex stage: every vertex once, in parallel. Shading the whole span is a post-transform cache that never
  // misses, which suits indexed meshes whose vertices are all referenced.
  constexpr std::size_t kVertexChunk = 2048;
  glm::vec4* clip = keep_clip ? clip_.data() : nullptr;
  detail::ProjectedVertex* projected = projected_.data();
  float* varyings = varyings_.data();
  const int width = target.width(), height = target.height();
  pool_.parallel_for((n + kVertexChunk - 1) / kVertexChunk, [&](std::size_t chunk, int) {
    const std::size_t end = std::min(n, (chunk + 1) * kVertexChunk);
    for (std::size_t i = chunk * kVertexChunk; i < end; ++i) {
      const VertexOut<Varyings> out = shader.vertex(vertices[i]);
      if (keep_clip) clip[i] = out.clip;
      if (project) projected[i] = detail::project_vertex(out.clip, width, height);
      const FloatArray<Varyings> f = to_floats(out.varyings);
      std::copy(f.begin(), f.end(), varyings + i * floats);
    }
  });

  const detail::ShadeContext<S> context{&shader, varyings, &state};
  const detail::VertexSource<S> source{&shader, vertices.data()};
  execute(target, {kind, clip, &detail::VertexSource<S>::clip_position, &source, projected, n, indices, &state, &detail::raster_tile<S>, &context,
                   detail::shades_deferred<S>(state)});
}

}  // namespace facet
