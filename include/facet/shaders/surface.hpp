// surface.hpp - SurfaceShader: per-pixel Phong or Blinn-Phong lighting of a textured, vertex-coloured material.
#pragma once

#include "facet/shaders/lit.hpp"

namespace facet {

// With one white directional light, ambient 0.15, specular 0.4, shininess 32 and SpecularModel::phong this is the
// reference fragment shader of BENCHMARK.md section 7.
struct SurfaceShader : LitUniforms {
  struct Varyings {
    glm::vec3 world;
    glm::vec3 normal;  // world space, not normalized until the pixel
    glm::vec4 color;
    glm::vec2 uv;
  };

  VertexOut<Varyings> vertex(const Vertex& v) const {
    const glm::vec4 p(v.position, 1.0f);
    return {transforms.clip_from_object * p,
            {glm::vec3(transforms.world_from_object * p), transforms.normal_from_object * v.normal, v.color, v.uv}};
  }
  // Back faces are lit with the normal reversed (two-sided lighting, as glTF asks of double-sided materials).
  glm::vec4 fragment(const Fragment<Varyings>& f) const {
    const glm::vec3 n = glm::normalize(f.varyings.normal);
    return shade(albedo(f), transforms.front_side(f.front_facing) ? n : -n, f.varyings.world);
  }
};

}  // namespace facet
