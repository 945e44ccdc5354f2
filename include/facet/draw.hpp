// draw.hpp - the pipeline's shader-specific stages: include it in a file that draws with a shader of its own.
#pragma once

#include <cstdint>
#include <new>
#include <span>
#include <type_traits>

#include "facet/detail/raster_tile.hpp"
#include "facet/detail/vertex_stage.hpp"
#include "facet/framebuffer.hpp"
#include "facet/render_state.hpp"
#include "facet/renderer.hpp"
#include "facet/shader.hpp"

namespace facet::detail {

// Renderer::draw, draw_lines and draw_points for shader S: the typed halves of the vertex stage and of the tile loop,
// handed to the shader-independent rest of the pipeline (Renderer::execute) as plain function pointers.
// A recorded draw's own copies of its shader and state, for the frame's tile pass.
template <class S>
struct RecordedDraw {
  RecordedDraw(const S& s, const RenderState& st) : shader(s), state(st), context{&shader, &state} {}
  RecordedDraw(const RecordedDraw&) = delete;
  RecordedDraw& operator=(const RecordedDraw&) = delete;
  S shader;
  RenderState state;
  ShadeContext<S> context;
};

template <class S>
struct DrawWith {
  using Vertex = typename S::Vertex;

  static void triangles(Renderer& renderer, Framebuffer& target, const S& shader, std::span<const Vertex> vertices,
                        std::span<const std::uint32_t> indices, const RenderState& state) {
    primitives(PrimitiveKind::triangles, renderer, target, shader, vertices, indices, state);
  }

  static void lines(Renderer& renderer, Framebuffer& target, const S& shader, std::span<const Vertex> vertices,
                    std::span<const std::uint32_t> indices, const RenderState& state) {
    primitives(PrimitiveKind::lines, renderer, target, shader, vertices, indices, state);
  }

  static void points(Renderer& renderer, Framebuffer& target, const S& shader, std::span<const Vertex> vertices,
                     std::span<const std::uint32_t> indices, const RenderState& state) {
    primitives(PrimitiveKind::points, renderer, target, shader, vertices, indices, state);
  }

  static void primitives(PrimitiveKind kind, Renderer& renderer, Framebuffer& target, const S& shader,
                         std::span<const Vertex> vertices, std::span<const std::uint32_t> indices,
                         const RenderState& state) {
    static_assert(std::is_copy_constructible_v<S>, "a shader must be copyable: a recorded draw keeps a copy");
    static_assert(alignof(RecordedDraw<S>) <= Renderer::kRecordAlign, "a shader may be aligned to 64 bytes at most");
    void* storage = renderer.record_storage(target, sizeof(RecordedDraw<S>));
    const auto* recorded = new (storage) RecordedDraw<S>(shader, state);
    if constexpr (!std::is_trivially_destructible_v<RecordedDraw<S>>)
      renderer.record_destructor(storage, [](void* p) { static_cast<RecordedDraw<S>*>(p)->~RecordedDraw(); });
    const VertexSource<S> source{&shader, vertices.data()};
    renderer.execute(target, {.kind = kind,
                              .vertex_count = vertices.size(),
                              .varying_floats = float_count_v<typename S::Varyings>,
                              .shade_vertices = &VertexSource<S>::shade,
                              .clip_position = &VertexSource<S>::clip_position,
                              .source = &source,
                              .indices = indices,
                              .state = &state,
                              .raster = target.samples() > 1 ? &raster_tile_multisample<S> : &raster_tile<S>,
                              .draw = &recorded->context});
  }
};

}  // namespace facet::detail
