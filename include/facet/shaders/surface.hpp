// surface.hpp - SurfaceShader: per-pixel Phong or Blinn-Phong lighting of a textured, vertex-coloured material.
#pragma once

#include <algorithm>
#include <cmath>

#include "facet/renderer.hpp"
#include "facet/shaders/lit.hpp"
#include "facet/shaders/masked.hpp"
#include "facet/shaders/normal_mapping.hpp"

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

  // A tangent-space normal map, or null (normal_mapping.hpp: applied without tangents).
  const Texture* normal_map = nullptr;
  float normal_scale = 1.0f;

  VertexOut<Varyings> vertex(const Vertex& v) const {
    const glm::vec4 p(v.position, 1.0f);
    return {transforms.clip_from_object * p,
            {glm::vec3(transforms.world_from_object * p), transforms.normal_from_object * v.normal, v.color, v.uv}};
  }
  // Back faces are lit with the normal reversed (two-sided lighting, as glTF asks of double-sided materials).
  glm::vec4 fragment(const Fragment<Varyings>& f) const {
    glm::vec3 n = glm::normalize(f.varyings.normal);
    if (!transforms.front_side(f.front_facing)) n = -n;
    if (normal_map) n = mapped_normal(n, f);
    return shade(albedo(f), n, f.varyings.world);
  }

  // fragment() for 16 pixels at once, the same operations in the same order, so both give identical images.
  // Texture samples and the specular pow() are taken lane by lane with the scalar functions; a normal-mapped
  // material is shaded by fragment() lane by lane.
  template <class L>
  FACET_LANES_INLINE simd::ColorT<L> fragment_lanes(const FragmentLanes<Varyings, L>& f) const {
    using namespace simd;
    FACET_LANE_TYPES(L);
    if (normal_map) return fragment_each_lane(*this, f);
    Vec3 n = normalize(f.get(&Varyings::normal));
    const Mask back = back_lanes(f.front_facing);
    n = Vec3{select(back, -n.x, n.x), select(back, -n.y, n.y), select(back, -n.z, n.z)};
    return shade_lanes(albedo_lanes(f), n, f.get(&Varyings::world));
  }

  glm::vec3 mapped_normal(glm::vec3 n, const Fragment<Varyings>& f) const {
    return facet::mapped_normal(n, f, *normal_map, surface.sampler, normal_scale);
  }
};

// SurfaceShader for a material with neither texture nor normal map: the same picture without the screen-space
// derivatives, which only texture level of detail and the normal map's frame read. Interpolating them triples
// the work per varying in the tile loop.
struct UntexturedSurfaceShader : SurfaceShader {
  static constexpr bool needs_derivatives = false;
};

}  // namespace facet

// The library compiles these pipelines once (src/scene/shaders/); programs link those instances.
FACET_EXTERN_SHADER(facet::SurfaceShader);
FACET_EXTERN_SHADER(facet::UntexturedSurfaceShader);
FACET_EXTERN_SHADER(facet::Masked<facet::SurfaceShader>);
