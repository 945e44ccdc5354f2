// punctual.hpp - the physically based look's lights as a pixel reads them: direction to the light and its falloff.
#pragma once

#include <algorithm>
#include <cmath>
#include <span>
#include <type_traits>

#include <glm/glm.hpp>

#include "facet/light.hpp"
#include "facet/shaders/brdf.hpp"
#include "facet/simd.hpp"

namespace facet {

class ShadowMap;

// A Light in the form the shader reads: colour times intensity, unit vectors, and the falloff of
// KHR_lights_punctual's recommended implementation: point and spot light fall off as 1 / d^2, windowed to zero at
// the range by saturate(1 - (d / range)^4); a spot's cone by saturate(cos(angle) * cone_scale + cone_offset)^2.
struct PunctualLight {
  glm::vec3 color{0.0f};    // times intensity
  glm::vec3 vector{0.0f};   // directional: unit direction towards the light; point, spot: position
  bool directional = true;
  glm::vec3 spot_direction{0.0f, 0.0f, -1.0f};  // unit; the way a spot shines
  float inverse_range_4 = 0.0f;                 // 1 / range^4; 0: unlimited
  float cone_scale = 0.0f, cone_offset = 1.0f;  // a point light: every direction at 1
  float outer_cone = 0.0f;                      // a spot's, for its shadow map
  bool casts_shadows = false;                   // a directional or spot light whose Light casts them
  const ShadowMap* shadow = nullptr;            // none: unshadowed

  bool is_spot() const { return cone_scale > 0.0f; }

  static PunctualLight from(const Light& light) {
    PunctualLight out;
    out.color = light.color * light.intensity;
    out.directional = light.kind == Light::Kind::directional;
    out.casts_shadows = light.casts_shadows && light.kind != Light::Kind::point;
    out.vector = out.directional ? glm::normalize(light.vector) : light.vector;
    if (light.range > 0.0f) {
      const float r2 = light.range * light.range;
      out.inverse_range_4 = 1.0f / (r2 * r2);
    }
    if (light.kind == Light::Kind::spot) {
      out.spot_direction = glm::normalize(light.spot_direction);
      const float cos_outer = std::cos(light.outer_cone), cos_inner = std::cos(light.inner_cone);
      out.cone_scale = 1.0f / std::max(0.001f, cos_inner - cos_outer);
      out.cone_offset = -cos_outer * out.cone_scale;
      out.outer_cone = light.outer_cone;
    }
    return out;
  }
};

// The unit direction l from a surface point towards the light and the factor its colour arrives with there.
template <class F, class V3>
FACET_LANES_INLINE void incident_light(const PunctualLight& light, const V3& world, V3& l, F& falloff) {
  using brdf::constant;
  if (light.directional) {
    if constexpr (std::is_same_v<V3, glm::vec3>) {
      l = light.vector;
    } else {
      l = V3{constant<F>(light.vector.x), constant<F>(light.vector.y), constant<F>(light.vector.z)};
    }
    falloff = constant<F>(1.0f);
    return;
  }
  const V3 d = light.vector - world;
  // Clamped so a surface at the light itself stays finite (three.js clamps d^2 at 0.01 m^2 the same way).
  const F d2 = brdf::max(dot(d, d), constant<F>(1e-4f));
  const F inverse_d = constant<F>(1.0f) / brdf::sqrt(d2);
  l = d * inverse_d;
  falloff = constant<F>(1.0f) / d2;
  if (light.inverse_range_4 > 0.0f) falloff = falloff * brdf::saturate(constant<F>(1.0f) - d2 * d2 * light.inverse_range_4);
  if (light.is_spot()) {
    const F cone = brdf::saturate(-dot(l, light.spot_direction) * light.cone_scale + light.cone_offset);
    falloff = falloff * cone * cone;
  }
}

}  // namespace facet
