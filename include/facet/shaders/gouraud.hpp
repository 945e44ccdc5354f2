// gouraud.hpp - GouraudShader: lighting evaluated per vertex, the light terms interpolated, albedo applied per pixel.
#pragma once

#include "facet/shader.hpp"
#include "facet/shaders/lighting.hpp"
#include "facet/shaders/mesh_vertex.hpp"
#include "facet/shaders/surface_color.hpp"

namespace facet {

struct GouraudShader {
  using Vertex = MeshVertex;
  // The diffuse and specular light terms travel separately so textures and face colours still modulate only the
  // diffuse part, as they would per pixel.
  struct Varyings {
    glm::vec3 diffuse;
    glm::vec3 specular;
    glm::vec4 color;
    glm::vec2 uv;
  };
  static constexpr bool may_discard = false;
  static constexpr bool needs_derivatives = true;

  ObjectTransforms transforms{};
  SurfaceColor surface{};
  LightBlock lights{};
  glm::vec3 specular{0.0f};
  float shininess = 32.0f;
  SpecularModel specular_model = SpecularModel::blinn_phong;
  glm::vec3 eye{0.0f};  // world space

  VertexOut<Varyings> vertex(const Vertex& v) const {
    const glm::vec4 p(v.position, 1.0f);
    const glm::vec3 world(transforms.world_from_object * p);
    const glm::vec3 n = glm::normalize(transforms.normal_from_object * v.normal);
    const LightTerms t = light_terms(lights, n, world, eye - world, shininess, specular_model,
                                     specular != glm::vec3(0.0f));
    return {transforms.clip_from_object * p, {t.diffuse, t.specular * specular, v.color, v.uv}};
  }
  glm::vec4 fragment(const Fragment<Varyings>& f) const {
    const glm::vec4 albedo = surface.albedo(f.varyings.color, f.primitive, f.varyings.uv, f.ddx.uv, f.ddy.uv);
    return glm::vec4(glm::vec3(albedo) * f.varyings.diffuse + f.varyings.specular, albedo.a);
  }
};

}  // namespace facet
