// gouraud.hpp - GouraudShader: lighting evaluated per vertex, the light terms interpolated, albedo applied per pixel.
#pragma once

#include "facet/shaders/lit.hpp"

namespace facet {

struct GouraudShader : LitUniforms {
  // The diffuse and specular light terms travel separately so textures and face colours still modulate only the
  // diffuse part, as they would per pixel.
  struct Varyings {
    glm::vec3 diffuse;
    glm::vec3 specular;
    glm::vec4 color;
    glm::vec2 uv;
  };

  VertexOut<Varyings> vertex(const Vertex& v) const {
    const glm::vec4 p(v.position, 1.0f);
    const glm::vec3 world(transforms.world_from_object * p);
    const LightTerms t = light_at(glm::normalize(transforms.normal_from_object * v.normal), world);
    return {transforms.clip_from_object * p, {t.diffuse, t.specular * specular, v.color, v.uv}};
  }
  glm::vec4 fragment(const Fragment<Varyings>& f) const {
    const glm::vec4 base = albedo(f);
    return glm::vec4(glm::vec3(base) * f.varyings.diffuse + f.varyings.specular, base.a);
  }
};

}  // namespace facet
