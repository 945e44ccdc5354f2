// flat.hpp - FlatShader: lit per pixel with one normal per face, so a face under directional light is one colour.
#pragma once

#include "facet/shaders/lit.hpp"

namespace facet {

struct FlatShader : LitUniforms {
  struct Varyings {
    glm::vec3 world;
    glm::vec4 color;
    glm::vec2 uv;
  };

  // Object-space normal of each triangle of the draw, indexed by Fragment::primitive; must not be null.
  const glm::vec3* face_normals = nullptr;

  VertexOut<Varyings> vertex(const Vertex& v) const {
    const glm::vec4 p(v.position, 1.0f);
    return {transforms.clip_from_object * p, {glm::vec3(transforms.world_from_object * p), v.color, v.uv}};
  }
  // Back faces are lit with the normal reversed (two-sided lighting).
  glm::vec4 fragment(const Fragment<Varyings>& f) const {
    const glm::vec3 n = glm::normalize(transforms.normal_from_object * face_normals[f.primitive]);
    return shade(albedo(f), transforms.front_side(f.front_facing) ? n : -n, f.varyings.world);
  }
};

}  // namespace facet
