// unlit.hpp - UnlitShader: albedo only (material x vertex colour x face colour x texture), no lighting.
#pragma once

#include "facet/fragment_lanes.hpp"
#include "facet/renderer.hpp"
#include "facet/shader.hpp"
#include "facet/shaders/masked.hpp"
#include "facet/shaders/mesh_vertex.hpp"
#include "facet/shaders/surface_color.hpp"
#include "facet/simd.hpp"

namespace facet {

struct UnlitShader {
  using Vertex = MeshVertex;
  struct Varyings {
    glm::vec4 color;
    glm::vec2 uv;
  };
  static constexpr bool may_discard = false;
  static constexpr bool needs_derivatives = true;  // texture level of detail

  glm::mat4 clip_from_object{1.0f};
  SurfaceColor surface{};

  VertexOut<Varyings> vertex(const Vertex& v) const {
    return {clip_from_object * glm::vec4(v.position, 1.0f), {v.color, v.uv}};
  }
  glm::vec4 fragment(const Fragment<Varyings>& f) const {
    return surface.albedo(f.varyings.color, f.primitive, f.varyings.uv, f.ddx.uv, f.ddy.uv);
  }
  // fragment() for 16 pixels at once, identical lane for lane.
  template <class L>
  FACET_LANES_INLINE simd::ColorT<L> fragment_lanes(const FragmentLanes<Varyings, L>& f) const {
    return surface.albedo_lanes(f);
  }
};

}  // namespace facet

// The library compiles these pipelines once (src/scene/shaders/); programs link those instances.
FACET_EXTERN_SHADER(facet::UnlitShader);
FACET_EXTERN_SHADER(facet::Masked<facet::UnlitShader>);
