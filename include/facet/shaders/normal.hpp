// normal.hpp - NormalShader: the world-space normal as a colour, n * 0.5 + 0.5.
#pragma once

#include "facet/fragment_lanes.hpp"
#include "facet/renderer.hpp"
#include "facet/shader.hpp"
#include "facet/shaders/mesh_vertex.hpp"
#include "facet/simd.hpp"

namespace facet {

struct NormalShader {
  using Vertex = MeshVertex;
  struct Varyings {
    glm::vec3 normal;
  };
  static constexpr bool may_discard = false;

  ObjectTransforms transforms{};

  VertexOut<Varyings> vertex(const Vertex& v) const {
    return {transforms.clip_from_object * glm::vec4(v.position, 1.0f), {transforms.normal_from_object * v.normal}};
  }
  glm::vec4 fragment(const Fragment<Varyings>& f) const {
    return glm::vec4(glm::normalize(f.varyings.normal) * 0.5f + 0.5f, 1.0f);
  }
  // fragment() for 16 pixels at once, identical lane for lane.
  static constexpr bool lanes_read_primitive = false;
  template <class L>
  FACET_LANES_INLINE simd::ColorT<L> fragment_lanes(const FragmentLanes<Varyings, L>& f) const {
    const simd::Vec3T<L> n = simd::normalize(f.get(&Varyings::normal));
    return {n.x * 0.5f + 0.5f, n.y * 0.5f + 0.5f, n.z * 0.5f + 0.5f, simd::splat<L>(1.0f)};
  }
};

}  // namespace facet

// The library compiles these pipelines once (src/scene/shaders/); programs link those instances.
FACET_EXTERN_SHADER(facet::NormalShader);
