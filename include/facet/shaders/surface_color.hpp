// surface_color.hpp - the albedo uniforms shared by the surface shaders: material colour, face colours, texture.
#pragma once

#include <cstdint>

#include <glm/glm.hpp>

#include "facet/texture.hpp"

namespace facet {

// albedo = diffuse * vertex colour * face colour (if any) * texture (if any). A missing source counts as white,
// so a mesh with one kind of colour gets exactly that colour times the material's.
struct SurfaceColor {
  glm::vec4 diffuse{1.0f};
  const glm::vec4* face_colors = nullptr;  // indexed by Fragment::primitive; nullptr = none
  const Texture* texture = nullptr;        // nullptr = none
  Sampler sampler{};
  bool opaque = false;  // alpha 1 whatever the sources say (AlphaMode::opaque)

  glm::vec4 albedo(glm::vec4 vertex_color, std::uint32_t primitive, glm::vec2 uv, glm::vec2 duv_dx,
                   glm::vec2 duv_dy) const {
    glm::vec4 c = diffuse * vertex_color;
    if (face_colors) c *= face_colors[primitive];
    if (texture) c *= texture->sample(uv, duv_dx, duv_dy, sampler);
    if (opaque) c.a = 1.0f;
    return c;
  }
};

}  // namespace facet
