// vertex_stage.hpp - the shader-specific vertex stage behind a function pointer, and the draw it feeds.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>

#include <glm/glm.hpp>

#include "facet/detail/binning.hpp"
#include "facet/detail/dispatch.hpp"
#include "facet/detail/triangle_setup.hpp"
#include "facet/render_state.hpp"
#include "facet/shader.hpp"
#include "facet/simd.hpp"
#include "facet/vertex_lanes.hpp"

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"

namespace facet::detail {

enum class PrimitiveKind { triangles, lines, points };

// Indices per primitive of each kind.
inline std::size_t indices_per_primitive(PrimitiveKind kind) {
  return kind == PrimitiveKind::triangles ? 3 : (kind == PrimitiveKind::lines ? 2 : 1);
}

// Where the vertex stage writes. The buffers hold the range of vertices [first, first + held): vertex i of the draw
// lands at index i - first, so a batch of primitives that references a narrow band of a large mesh needs post-transform
// memory for that band only.
struct VertexOutputs {
  std::size_t first;
  glm::vec4* clip;             // clip positions, or nullptr when the draw does not keep them
  ProjectedVertex* projected;  // projected and snapped positions, or nullptr (lines)
  float* varyings;             // `floats` per vertex
  int width, height;
};

// Vertices [first, end) of a draw; empty when first >= end.
struct VertexRange {
  std::size_t first = 0, end = 0;
};

// Recomputes one vertex's clip-space position (the shader's vertex function again). The vertex stage keeps no
// clip positions for triangles: only the few that cross the frustum need them, and they ask for them here.
using ClipPositionFn = glm::vec4 (*)(const void* source, std::uint32_t vertex);

// Shades vertices [begin, end) of the draw into `out`.
using VertexStageFn = void (*)(const void* source, std::size_t begin, std::size_t end, const VertexOutputs& out);

// A draw's shader and vertices: the typed half of the vertex stage, reached through plain function pointers once
// per chunk of vertices (the loop inside is inlined and specialised for the shader).
template <Shader S>
struct VertexSource {
  const S* shader;
  const typename S::Vertex* vertices;

  // The shader runs on 16 vertices per call if it has vertex_lanes, else on one; each block's clip positions are
  // then projected together (see ClipBlock). Compiled per CPU level like raster_tile, for the lane types.
  static void shade(const void* source, std::size_t begin, std::size_t end, const VertexOutputs& out) {
    at_shader_level<ShaderTraits<S>::vertex_lanes_per_level>([&]<class L>(L) __attribute__((always_inline)) {
      using Varyings = typename S::Varyings;
      constexpr std::size_t kFloats = float_count_v<Varyings>;
      const auto& self = *static_cast<const VertexSource*>(source);
      ClipBlock block;
      for (std::size_t first = begin; first < end; first += kProjectBlock) {
        const std::size_t count = std::min(kProjectBlock, end - first);
        std::size_t k = 0;
        if constexpr (ShaderTraits<S>::vertex_lanes) {
          for (; k + simd::kLanes <= count; k += simd::kLanes) {
            const VertexOutLanes<Varyings, L> shaded =
                self.shader->vertex_lanes(VertexLanes<typename S::Vertex, L>{self.vertices + first + k});
            simd::store(block.x + k, shaded.clip_x), simd::store(block.y + k, shaded.clip_y);
            simd::store(block.z + k, shaded.clip_z), simd::store(block.w + k, shaded.clip_w);
            float* varyings = out.varyings + (first + k - out.first) * kFloats;
            for (int lane = 0; lane < simd::kLanes; ++lane)
              for (std::size_t f = 0; f < kFloats; ++f) varyings[lane * kFloats + f] = shaded.varyings[f][lane];
          }
        }
        for (; k < count; ++k) {
          const VertexOut<Varyings> shaded = self.shader->vertex(self.vertices[first + k]);
          block.x[k] = shaded.clip.x, block.y[k] = shaded.clip.y;
          block.z[k] = shaded.clip.z, block.w[k] = shaded.clip.w;
          const FloatArray<Varyings> f = to_floats(shaded.varyings);
          std::copy(f.begin(), f.end(), out.varyings + (first + k - out.first) * kFloats);
        }
        if (out.clip)
          for (std::size_t j = 0; j < count; ++j)
            out.clip[first + j - out.first] = {block.x[j], block.y[j], block.z[j], block.w[j]};
        if (out.projected) project_vertices(block, count, out.projected + (first - out.first), out.width, out.height);
      }
    });
  }

  // The same clip position again, for the few triangles that cross the frustum (see ClipPositionFn).
  static glm::vec4 clip_position(const void* source, std::uint32_t vertex) {
    const auto& self = *static_cast<const VertexSource*>(source);
    return self.shader->vertex(self.vertices[vertex]).clip;
  }
};

using TileRasterFn = void (*)(const void* draw, const TileWork& work);

struct DrawRequest {
  PrimitiveKind kind;
  std::size_t vertex_count;
  std::size_t varying_floats;  // per vertex
  VertexStageFn shade_vertices;
  ClipPositionFn clip_position;
  const void* source;  // what shade_vertices and clip_position read
  std::span<const std::uint32_t> indices;
  const RenderState* state;
  TileRasterFn raster;
  const void* draw;  // what `raster` reads: the recorded draw's copies of shader and state (Renderer::record_copy)
};

}  // namespace facet::detail

#pragma GCC diagnostic pop
