// surface_color.hpp - the albedo uniforms shared by the surface shaders: material colour, face colours, texture.
#pragma once

#include <cstddef>
#include <cstdint>

#include <glm/glm.hpp>

#include "facet/fragment_lanes.hpp"
#include "facet/simd.hpp"
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

  // albedo() for 16 pixels, the same operations in the same order, for varyings with members `color` and `uv`.
  // Texture samples are taken lane by lane with the scalar function.
  template <class V, class L>
  FACET_LANES_INLINE simd::ColorT<L> albedo_lanes(const FragmentLanes<V, L>& f) const {
    using namespace simd;
    FACET_LANE_TYPES(L);
    const Color vertex = f.get(&V::color);
    const glm::vec4 d = diffuse;
    Color c{d.r * vertex.r, d.g * vertex.g, d.b * vertex.b, d.a * vertex.a};
    if (face_colors) {
      for (int k = 0; k < kLanes; ++k) {
        const glm::vec4 face = face_colors[f.primitive[k]];
        c.r[k] *= face.r, c.g[k] *= face.g, c.b[k] *= face.b, c.a[k] *= face.a;
      }
    }
    if (texture) {
      const Vec2 uv = f.get(&V::uv);
      const std::size_t u = FragmentLanes<V>::float_index(&V::uv);
      for (int k = 0; k < kLanes; ++k) {
        const glm::vec4 t = texture->sample(glm::vec2(uv.x[k], uv.y[k]), glm::vec2(f.ddx[u][k], f.ddx[u + 1][k]),
                                            glm::vec2(f.ddy[u][k], f.ddy[u + 1][k]), sampler);
        c.r[k] *= t.r, c.g[k] *= t.g, c.b[k] *= t.b, c.a[k] *= t.a;
      }
    }
    if (opaque) c.a = splat<L>(1.0f);
    return c;
  }
};

}  // namespace facet
