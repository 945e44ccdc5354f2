// lit.hpp - LitUniforms: the material, light and camera uniforms the lit stock shaders (flat, Gouraud, surface) share.
#pragma once

#include "facet/shader.hpp"
#include "facet/shaders/lighting.hpp"
#include "facet/shaders/mesh_vertex.hpp"
#include "facet/shaders/surface_color.hpp"

namespace facet {

// A plain base struct, not an interface: each lit shader derives from it and adds its own Varyings, vertex() and
// fragment(), so the pipeline is still instantiated on one concrete type with no virtual call. The shaders differ
// only in where the normal comes from and whether lighting runs per vertex or per pixel.
struct LitUniforms {
  using Vertex = MeshVertex;
  static constexpr bool may_discard = false;
  static constexpr bool needs_derivatives = true;  // the uv derivatives pick the texture's mipmap level

  ObjectTransforms transforms{};
  SurfaceColor surface{};
  LightBlock lights{};
  glm::vec3 specular{0.0f};
  float shininess = 32.0f;
  SpecularModel specular_model = SpecularModel::blinn_phong;
  glm::vec3 eye{0.0f};  // world space

  // The surface colour at a pixel, for varyings that carry the vertex colour and uv.
  template <class V>
  glm::vec4 albedo(const Fragment<V>& f) const {
    return surface.albedo(f.varyings.color, f.primitive, f.varyings.uv, f.ddx.uv, f.ddy.uv);
  }
  // What the lights contribute at world point `world` with unit normal n; skips the specular pow() when the
  // material has no specular colour.
  LightTerms light_at(glm::vec3 n, glm::vec3 world) const {
    return light_terms(lights, n, world, eye - world, shininess, specular_model, specular != glm::vec3(0.0f));
  }
  // `albedo` lit at world point `world` with unit normal n; alpha passes through.
  glm::vec4 shade(glm::vec4 albedo, glm::vec3 n, glm::vec3 world) const {
    return glm::vec4(shade_lit(lights, glm::vec3(albedo), specular, shininess, specular_model, n, world, eye - world),
                     albedo.a);
  }
};

}  // namespace facet
