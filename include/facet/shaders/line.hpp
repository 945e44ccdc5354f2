// line.hpp - LineShader: one constant colour, for wireframes and edge overlays.
#pragma once

#include "facet/renderer.hpp"
#include "facet/shader.hpp"
#include "facet/shaders/mesh_vertex.hpp"

namespace facet {

struct LineShader {
  using Vertex = MeshVertex;
  struct Varyings {
    float unused;  // a varyings struct cannot be empty
  };
  static constexpr bool may_discard = false;

  glm::mat4 clip_from_object{1.0f};
  glm::vec4 color{1.0f};

  VertexOut<Varyings> vertex(const Vertex& v) const { return {clip_from_object * glm::vec4(v.position, 1.0f), {0.0f}}; }
  glm::vec4 fragment(const Fragment<Varyings>&) const { return color; }
};

}  // namespace facet

// The library compiles these pipelines once (src/scene/shaders/); programs link those instances.
FACET_EXTERN_SHADER(facet::LineShader);
