// depth.hpp - DepthShader: linear eye-space depth as grey, white at `near`, black at `far`.
#pragma once

#include <algorithm>

#include "facet/fragment_lanes.hpp"
#include "facet/renderer.hpp"
#include "facet/shader.hpp"
#include "facet/shaders/mesh_vertex.hpp"
#include "facet/simd.hpp"

namespace facet {

struct DepthShader {
  using Vertex = MeshVertex;
  struct Varyings {
    float eye_depth;  // linear in eye space, so perspective-correct interpolation keeps it exact
  };
  static constexpr bool may_discard = false;

  glm::mat4 clip_from_object{1.0f};
  glm::mat4 view_from_object{1.0f};
  float near = 0.1f, far = 100.0f;

  VertexOut<Varyings> vertex(const Vertex& v) const {
    const glm::vec4 p(v.position, 1.0f);
    return {clip_from_object * p, {-(view_from_object * p).z}};
  }
  glm::vec4 fragment(const Fragment<Varyings>& f) const {
    const float t = far > near ? (f.varyings.eye_depth - near) / (far - near) : 0.0f;
    const float grey = 1.0f - std::clamp(t, 0.0f, 1.0f);
    return glm::vec4(grey, grey, grey, 1.0f);
  }
  // fragment() for 16 pixels at once, identical lane for lane (std::clamp's comparisons, in its order).
  static constexpr bool lanes_read_primitive = false;
  template <class L>
  FACET_LANES_INLINE simd::ColorT<L> fragment_lanes(const FragmentLanes<Varyings, L>& f) const {
    using namespace simd;
    FACET_LANE_TYPES(L);
    const Float t = far > near ? (f.get(&Varyings::eye_depth) - near) / (far - near) : splat<L>(0.0f);
    const Float grey = 1.0f - select(t < 0.0f, splat<L>(0.0f), select(1.0f < t, splat<L>(1.0f), t));
    return {grey, grey, grey, splat<L>(1.0f)};
  }
};

}  // namespace facet

// The library compiles these pipelines once (src/scene/shaders/); programs link those instances.
FACET_EXTERN_SHADER(facet::DepthShader);
