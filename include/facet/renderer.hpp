// renderer.hpp - the pipeline front door: clear, draw triangles or lines with a Shader, finish.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <glm/glm.hpp>
#include <memory>
#include <span>

#include "facet/framebuffer.hpp"
#include "facet/render_state.hpp"
#include "facet/shader.hpp"

namespace facet {

class Renderer;

namespace detail {
struct DrawRequest;
// The pipeline compiled for shader S: defined in facet/draw.hpp, which a file drawing with S must include.
template <class S>
struct DrawWith;
}  // namespace detail

// Counters of the last draw, for tests and tuning.
struct DrawStats {
  std::size_t primitives = 0;       // submitted
  std::size_t culled = 0;           // back/front-face or zero area
  std::size_t clipped = 0;          // crossed a frustum plane and were split
  std::size_t invalid = 0;          // referenced a vertex outside the vertex span; skipped
  std::size_t binned = 0;           // set-up triangles that reached rasterization
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

  int threads() const;

  // Calls body(i) for every i in [0, count) on the renderer's threads and returns when all are done, each index
  // exactly once, in no set order: for passes over a frame's buffers between draws (ambient occlusion).
  void parallel_for(std::size_t count, const std::function<void(std::size_t)>& body);

  // Records a clear; each tile applies it as the frame's tile pass loads it (while hot in cache) or at finish().
  // Draws recorded for `target` before it are drawn first.
  void clear(Framebuffer& target, glm::vec4 color = {0, 0, 0, 1}, float depth = 1.0f);

  // A frame's draws are recorded and drawn together at finish(): each tile is rasterized once, with every draw that
  // touches it in the order they were made, in memory its thread owns (so samples never need full-size planes).
  // A draw shades its vertices and sets up and bins its primitives before it returns, so its vertex and index spans
  // may change or go at once; it keeps a copy of the shader and the state, and what the shader points to
  // (textures, environments, lights, arrays) must stay alive and unchanged until finish(). Between draw() and
  // finish() the framebuffer's contents are not yet drawn: mutable_color() and mutable_depth() draw the recorded
  // work first, a draw to another framebuffer draws it first, and a framebuffer destroyed meanwhile drops it. A
  // frame whose recorded work passes recorded_bytes_limit() is drawn in parts (below).
  //
  // Draws indexed triangles (3 indices each, counter-clockwise front faces). Indices outside the vertex span skip
  // their triangle. The pixels are in `target` after finish(). The stock shaders are compiled into the library
  // (facet/shaders/stock.hpp); drawing with a shader of your own compiles the pipeline for it, which needs
  // #include <facet/draw.hpp> (without it, detail::DrawWith<S> is an incomplete type).
  template <Shader S>
  void draw(Framebuffer& target, const S& shader, std::span<const typename S::Vertex> vertices,
            std::span<const std::uint32_t> indices, const RenderState& state = {});

  // Draws indexed line segments (2 indices each), state.line_width pixels wide, never culled.
  template <Shader S>
  void draw_lines(Framebuffer& target, const S& shader, std::span<const typename S::Vertex> vertices,
                  std::span<const std::uint32_t> indices, const RenderState& state = {});

  // Draws indexed points (1 index each), as OpenGL's GL_POINTS: each point whose position lies inside the view
  // volume covers the pixel centres within a screen-aligned square of state.point_size pixels a side centred on it
  // (PointShape::square), or within a disc of that diameter (PointShape::disc, drawn as a polygon whose edges stay
  // within a tenth of a pixel of the circle), at the point's depth; every pixel takes the vertex's varyings. Never
  // culled; the painter's order does not apply. With state.point_size_per_w, each point's size follows its depth.
  template <Shader S>
  void draw_points(Framebuffer& target, const S& shader, std::span<const typename S::Vertex> vertices,
                   std::span<const std::uint32_t> indices, const RenderState& state = {});

  // Draws the frame recorded so far (whichever framebuffer it is for) and applies clears no draw has touched. Call
  // before reading the framebuffer.
  void finish(Framebuffer& target);

  const DrawStats& last_stats() const { return stats_; }

  // The memory a recorded frame may hold (set-up primitives, bins and varyings) before the work recorded so far is
  // drawn, ahead of finish(); the frame then goes on in another tile pass, and a multisampled target keeps
  // full-size sample planes (Framebuffer::keep_samples) so that every sample continues exactly: the image is the
  // same. Default kDefaultRecordedBytes, about 800,000 visible triangles; 0 draws each batch as soon as the next
  // one comes. Within the limit, parts are smaller still: a target that has every plane a part continues from (a
  // single-sample one, or one holding sample planes) draws parts of at most kCachedRecordedBytes (about one batch
  // of a dense mesh), as a tile pass that reads its set-up work back from the cache costs less than the loads and
  // stores of the tiles each extra part touches. A multisampled target without sample planes records up to the
  // limit itself, as holding them costs fresh memory (66 MB for 4 samples at 1920x1080), unless a draw would bring
  // the frame's recorded work past the planes' weight on a target whose planes weigh 16 MiB or more: it then takes
  // the planes and goes on in cached parts (a million-point cloud at 4 samples peaks at 221 MiB instead of 345).
  // Consecutive draws in the painter's order, which are composited together per tile, record up to the limit.
  static constexpr std::size_t kDefaultRecordedBytes = std::size_t{128} << 20;
  static constexpr std::size_t kCachedRecordedBytes = std::size_t{2} << 20;
  void set_recorded_bytes_limit(std::size_t bytes);
  std::size_t recorded_bytes_limit() const;

 private:
  template <class S>
  friend struct detail::DrawWith;
  friend class Framebuffer;
  static constexpr std::size_t kRecordAlign = 64;
  // Memory for a recorded draw's copies of its shader and state (aligned to kRecordAlign), alive until the frame
  // recorded for `target` is drawn or dropped; draws recorded for another framebuffer are drawn first. An object
  // built there that needs destroying registers how with record_destructor.
  void* record_storage(Framebuffer& target, std::size_t bytes);
  void record_destructor(void* object, void (*destroy)(void*));
  // Records one draw's batches (see Work).
  void execute(Framebuffer& target, const detail::DrawRequest& request);
  // The tile pass over the frame recorded so far (see draw_recorded_tiles for store_depth), then drop_recorded.
  void flush_recorded(bool store_depth = true);
  // Forgets the recorded frame: its batches, varyings and copies.
  void drop_recorded();
  // store_depth false: the frame's last tile pass, for a target that does not keep its depth.
  void draw_recorded_tiles(bool store_depth);
  void release_batches();

  // The thread pool and the frame's work buffers (post-transform vertices, the recorded batches, tile order,
  // per-thread tile memory and scratch), reused from frame to frame; defined in src/core/renderer.cpp.
  struct Work;
  std::unique_ptr<Work> work_;
  DrawStats stats_;
};

// Not inline, so that FACET_EXTERN_SHADER keeps a file that draws with a shader compiled elsewhere from needing
// detail::DrawWith (an extern template's inline functions may still be instantiated for inlining).
template <Shader S>
void Renderer::draw(Framebuffer& target, const S& shader, std::span<const typename S::Vertex> vertices,
                    std::span<const std::uint32_t> indices, const RenderState& state) {
  detail::DrawWith<S>::triangles(*this, target, shader, vertices, indices, state);
}

template <Shader S>
void Renderer::draw_lines(Framebuffer& target, const S& shader, std::span<const typename S::Vertex> vertices,
                          std::span<const std::uint32_t> indices, const RenderState& state) {
  detail::DrawWith<S>::lines(*this, target, shader, vertices, indices, state);
}

template <Shader S>
void Renderer::draw_points(Framebuffer& target, const S& shader, std::span<const typename S::Vertex> vertices,
                           std::span<const std::uint32_t> indices, const RenderState& state) {
  detail::DrawWith<S>::points(*this, target, shader, vertices, indices, state);
}

}  // namespace facet

// Compiling the pipeline for a shader is the costly part of building a program that draws: its per-tile loop is
// compiled once per CPU level. A program that draws with one shader from several source files can compile it once:
// FACET_EXTERN_SHADER(S) after the shader's definition in a header those files include, and
// FACET_INSTANTIATE_SHADER(S) in one .cpp file, which includes facet/draw.hpp. The library does this for its stock
// shaders.
#define FACET_SHADER_DRAWS_(prefix, S)                                                                      \
  prefix void ::facet::Renderer::draw<S>(::facet::Framebuffer&, const S&, std::span<const S::Vertex>,       \
                                         std::span<const std::uint32_t>, const ::facet::RenderState&);      \
  prefix void ::facet::Renderer::draw_lines<S>(::facet::Framebuffer&, const S&, std::span<const S::Vertex>, \
                                               std::span<const std::uint32_t>, const ::facet::RenderState&);    \
  prefix void ::facet::Renderer::draw_points<S>(::facet::Framebuffer&, const S&, std::span<const S::Vertex>, \
                                                std::span<const std::uint32_t>, const ::facet::RenderState&)
#define FACET_EXTERN_SHADER(S) FACET_SHADER_DRAWS_(extern template, S)
#define FACET_INSTANTIATE_SHADER(S) FACET_SHADER_DRAWS_(template, S)
