// gouraud.hpp - GouraudShader: lighting evaluated per vertex, the light terms interpolated, albedo applied per pixel.
#pragma once

#include "facet/renderer.hpp"
#include "facet/shaders/lit.hpp"

namespace facet {

struct GouraudShader : LitUniforms {
  // The diffuse and specular light terms travel separately so textures and face colours still modulate only the
  // diffuse part, as they would per pixel. Each vertex is lit from both sides; a back face takes the back side's
  // terms (two-sided lighting).
  struct Varyings {
    glm::vec3 diffuse, back_diffuse;
    glm::vec3 specular, back_specular;
    glm::vec4 color;
    glm::vec2 uv;
  };

  VertexOut<Varyings> vertex(const Vertex& v) const {
    const glm::vec4 p(v.position, 1.0f);
    const glm::vec3 world(transforms.world_from_object * p);
    const glm::vec3 n = glm::normalize(transforms.normal_from_object * v.normal);
    const LightTerms front = light_at(n, world), back = light_at(-n, world);
    return {transforms.clip_from_object * p,
            {front.diffuse, back.diffuse, front.specular * specular, back.specular * specular, v.color, v.uv}};
  }
  glm::vec4 fragment(const Fragment<Varyings>& f) const {
    const glm::vec4 base = albedo(f);
    const bool front = transforms.front_side(f.front_facing);
    return glm::vec4(glm::vec3(base) * (front ? f.varyings.diffuse : f.varyings.back_diffuse) +
                         (front ? f.varyings.specular : f.varyings.back_specular),
                     base.a);
  }

  // fragment() for 16 pixels at once, the same operations in the same order, so both give identical images.
  template <class L>
  FACET_LANES_INLINE simd::ColorT<L> fragment_lanes(const FragmentLanes<Varyings, L>& f) const {
    using namespace simd;
    FACET_LANE_TYPES(L);
    const Color base = albedo_lanes(f);
    const Mask back = back_lanes(f.front_facing);
    const Vec3 d = f.get(&Varyings::diffuse), back_d = f.get(&Varyings::back_diffuse);
    const Vec3 s = f.get(&Varyings::specular), back_s = f.get(&Varyings::back_specular);
    return {base.r * select(back, back_d.x, d.x) + select(back, back_s.x, s.x),
            base.g * select(back, back_d.y, d.y) + select(back, back_s.y, s.y),
            base.b * select(back, back_d.z, d.z) + select(back, back_s.z, s.z), base.a};
  }
};

}  // namespace facet

// The library compiles these pipelines once (src/scene/shaders/); programs link those instances.
FACET_EXTERN_SHADER(facet::GouraudShader);
