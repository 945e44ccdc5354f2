// environment_background.hpp - EnvironmentBackgroundShader: the environment seen behind the model, tone-mapped.
#pragma once

#include "facet/environment.hpp"
#include "facet/fragment_lanes.hpp"
#include "facet/renderer.hpp"
#include "facet/shader.hpp"
#include "facet/shaders/brdf.hpp"
#include "facet/shaders/pbr.hpp"
#include "facet/simd.hpp"

namespace facet {

// Drawn as one triangle covering the target (its vertices in NDC) before the model: each pixel shows the
// environment's radiance along its view ray, prefiltered at `blur` (a roughness: 0 sharp, 1 the roughest level),
// through the same exposure, tone curve and encoding as the physically based look.
struct EnvironmentBackgroundShader {
  struct Vertex {
    glm::vec2 ndc;
  };
  struct Varyings {
    glm::vec3 direction;  // world space, not normalized until the pixel
  };
  static constexpr bool may_discard = false;
  static constexpr bool lanes_read_primitive = false;

  glm::mat4 world_from_clip{1.0f};
  glm::vec3 eye{0.0f};
  const Environment* environment = nullptr;
  float blur = 0.0f;
  ToneMapping tone_mapping = ToneMapping::neutral;
  float exposure = 1.0f;

  // The ray through a point of the far plane, p.xyz - eye p.w, is linear in NDC for perspective and parallel
  // projections alike (p's w is constant for a parallel one), so it interpolates exactly across the triangle.
  VertexOut<Varyings> vertex(const Vertex& v) const {
    const glm::vec4 p = world_from_clip * glm::vec4(v.ndc, 1.0f, 1.0f);
    const glm::vec4 near = world_from_clip * glm::vec4(v.ndc, -1.0f, 1.0f);
    // Parallel: every ray has the view direction, from the near to the far plane.
    const bool parallel = p.w == near.w;
    const glm::vec3 direction = parallel ? glm::vec3(p) / p.w - glm::vec3(near) / near.w : glm::vec3(p) - eye * p.w;
    return {glm::vec4(v.ndc, 1.0f, 1.0f), {direction}};
  }

  glm::vec4 fragment(const Fragment<Varyings>& f) const {
    const glm::vec3 l = environment->radiance(glm::normalize(f.varyings.direction), blur);
    const brdf::Rgb<float> c = PbrShader::encode(brdf::tone_map(brdf::Rgb<float>{l.r, l.g, l.b}, tone_mapping, exposure));
    return {c.r, c.g, c.b, 1.0f};
  }

  // fragment() for 16 pixels, the same operations in the same order.
  template <class L>
  FACET_LANES_INLINE simd::ColorT<L> fragment_lanes(const FragmentLanes<Varyings, L>& f) const {
    using namespace simd;
    FACET_LANE_TYPES(L);
    const Vec3 l = environment->radiance(normalize(f.get(&Varyings::direction)), splat<L>(blur));
    const brdf::Rgb<Float> c = PbrShader::encode(brdf::tone_map(brdf::Rgb<Float>{l.x, l.y, l.z}, tone_mapping, exposure));
    return {c.r, c.g, c.b, splat<L>(1.0f)};
  }
};

}  // namespace facet

// The library compiles these pipelines once (src/scene/shaders/); programs link those instances.
FACET_EXTERN_SHADER(facet::EnvironmentBackgroundShader);
