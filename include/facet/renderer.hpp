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
#include "facet/detail/vertex_stage.hpp"

namespace facet {

// Counters of the last draw, for tests and tuning.
struct DrawStats {
  std::size_t primitives = 0;  // submitted
  std::size_t culled = 0;      // back/front-face or zero area
  std::size_t clipped = 0;     // crossed a frustum plane and were split
  std::size_t invalid = 0;     // referenced a vertex outside the vertex span; skipped
  std::size_t binned = 0;      // set-up triangles that reached rasterization
  std::size_t vertices_shaded = 0;  // vertex shader runs (batches of large meshes repeat their shared vertices)
  std::size_t vertices_held = 0;    // post-transform vertices stored at once: the band of one batch, or all
};

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
  detail::VertexOutputs prepare_vertex_outputs(const detail::DrawRequest& request, std::size_t held,
                                               std::size_t first, int width, int height);
  detail::VertexRange batch_vertex_band(const detail::DrawRequest& request, std::size_t batch_first,
                                        std::size_t batch_count);
  void shade_vertex_range(const detail::DrawRequest& request, const detail::VertexOutputs& out, std::size_t begin,
                          std::size_t end);

  detail::ThreadPool pool_;
  // Post-transform vertices of the range being drawn (see VertexOutputs).
  std::vector<glm::vec4> clip_;     // clip positions, kept only for lines and the painter's sort
  std::vector<detail::ProjectedVertex> projected_;  // the same after the divide, viewport and snapping
  std::vector<float> varyings_;     // varyings, float_count floats per vertex
  std::vector<detail::SetupChunk> chunks_;
  std::vector<detail::VertexRange> chunk_bands_;  // vertices each setup chunk of the batch references
  std::vector<std::uint32_t> order_;  // painter's order
  std::vector<float> sort_keys_;
  std::vector<std::uint64_t> active_tiles_;  // tiles with work, most binned triangles first (see execute)
  std::vector<detail::TileScratch> scratch_;  // one per thread, for deferred shading
  DrawStats stats_;
};

}  // namespace facet

// Compiling the pipeline for a shader is the costly part of building a program that draws: its per-tile loop is
// compiled once per CPU level. A program that draws with one shader from several source files can compile it once:
// FACET_EXTERN_SHADER(S) after the shader's definition in a header those files include, and
// FACET_INSTANTIATE_SHADER(S) in one .cpp file. The library does this for its stock shaders.
#define FACET_SHADER_DRAWS_(prefix, S)                                                                             \
  prefix void ::facet::Renderer::draw<S>(::facet::Framebuffer&, const S&, std::span<const S::Vertex>,              \
                                         std::span<const std::uint32_t>, const ::facet::RenderState&);             \
  prefix void ::facet::Renderer::draw_lines<S>(::facet::Framebuffer&, const S&, std::span<const S::Vertex>,        \
                                               std::span<const std::uint32_t>, const ::facet::RenderState&)
#define FACET_EXTERN_SHADER(S) FACET_SHADER_DRAWS_(extern template, S)
#define FACET_INSTANTIATE_SHADER(S) FACET_SHADER_DRAWS_(template, S)

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
  const detail::ShadeContext<S> context{&shader, &state};
  const detail::VertexSource<S> source{&shader, vertices.data()};
  execute(target, {kind, vertices.size(), float_count_v<typename S::Varyings>, &detail::VertexSource<S>::shade,
                   &detail::VertexSource<S>::clip_position, &source, indices, &state, &detail::raster_tile<S>, &context,
                   detail::shades_deferred<S>(state)});
}

}  // namespace facet
