// normal_mapping.hpp - a tangent-space normal map applied without tangents, by the cotangent frame of the pixel.
#pragma once

#include <algorithm>
#include <cmath>

#include <glm/glm.hpp>

#include "facet/shader.hpp"
#include "facet/texture.hpp"

namespace facet {

// The frame comes from the screen-space derivatives of the world position and the uvs (a cotangent frame, as in
// Schueler's "Normal Mapping without Precomputed Tangents"), so meshes need no tangents. `V` has members `world`
// and the map's uvs (`uv` unless `uvs` names another); n is the unit interpolated normal. Returns n where the uvs
// do not vary over the pixel.
template <class V>
glm::vec3 mapped_normal(glm::vec3 n, const Fragment<V>& f, const Texture& map, const Sampler& sampler, float scale,
                        glm::vec2 V::*uvs = &V::uv) {
  // Window y grows downwards; the frame is built for y up, as OpenGL's dFdy gives it.
  const glm::vec3 dp1 = f.ddx.world, dp2 = -f.ddy.world;
  const glm::vec2 duv1 = f.ddx.*uvs, duv2 = -(f.ddy.*uvs);
  const glm::vec3 dp2perp = glm::cross(dp2, n), dp1perp = glm::cross(n, dp1);
  const glm::vec3 t = dp2perp * duv1.x + dp1perp * duv2.x, b = dp2perp * duv1.y + dp1perp * duv2.y;
  const float extent = std::max(glm::dot(t, t), glm::dot(b, b));
  if (!(extent > 0.0f) || !std::isfinite(extent)) return n;  // uvs constant over the pixel: no frame
  const float inverse = 1.0f / std::sqrt(extent);
  const glm::vec3 texel = glm::vec3(map.sample(f.varyings.*uvs, f.ddx.*uvs, f.ddy.*uvs, sampler));
  const glm::vec3 m = texel * 2.0f - 1.0f;
  const glm::vec3 mapped = t * (inverse * m.x * scale) + b * (inverse * m.y * scale) + n * m.z;
  const float length = glm::length(mapped);
  return length > 0.0f && std::isfinite(length) ? mapped / length : n;
}

}  // namespace facet
