// flat.hpp - FlatShader: lit per pixel with one normal per face, so a face under directional light is one colour.
#pragma once

#include <cstdint>

#include "facet/shader.hpp"
#include "facet/shaders/lighting.hpp"
#include "facet/shaders/mesh_vertex.hpp"
#include "facet/shaders/surface_color.hpp"

namespace facet {

struct FlatShader {
  using Vertex = MeshVertex;
  struct Varyings {
    glm::vec3 world;
    glm::vec4 color;
    glm::vec2 uv;
  };
  static constexpr bool may_discard = false;
  static constexpr bool needs_derivatives = true;

  ObjectTransforms transforms{};
  // Object-space normal of each triangle of the draw, indexed by Fragment::primitive; must not be null.
  const glm::vec3* face_normals = nullptr;
  SurfaceColor surface{};
  LightBlock lights{};
  glm::vec3 specular{0.0f};
  float shininess = 32.0f;
  SpecularModel specular_model = SpecularModel::blinn_phong;
  glm::vec3 eye{0.0f};  // world space

  VertexOut<Varyings> vertex(const Vertex& v) const {
    const glm::vec4 p(v.position, 1.0f);
    return {transforms.clip_from_object * p, {glm::vec3(transforms.world_from_object * p), v.color, v.uv}};
  }
  glm::vec4 fragment(const Fragment<Varyings>& f) const {
    const glm::vec3 n = glm::normalize(transforms.normal_from_object * face_normals[f.primitive]);
    const glm::vec4 albedo = surface.albedo(f.varyings.color, f.primitive, f.varyings.uv, f.ddx.uv, f.ddy.uv);
    return glm::vec4(shade_lit(lights, glm::vec3(albedo), specular, shininess, specular_model, n, f.varyings.world,
                               eye - f.varyings.world),
                     albedo.a);
  }
};

}  // namespace facet
