// normal_mapping.hpp - a tangent-space normal map applied by the mesh's tangents or the pixel's cotangent frame.
#pragma once

#include <algorithm>
#include <cmath>

#include <glm/glm.hpp>

#include "facet/shader.hpp"
#include "facet/texture.hpp"

namespace facet {

// The map's texel at the pixel, read in the frame (t, b, n): t and b weighted by `frame_scale` times the map's
// scale, then normalised; n where that has no length. Both frames below end here.
template <class V>
glm::vec3 apply_normal_map(glm::vec3 t, glm::vec3 b, glm::vec3 n, float frame_scale, const Fragment<V>& f,
                           const Texture& map, const Sampler& sampler, float scale, glm::vec2 V::*uvs) {
  const glm::vec3 texel = glm::vec3(map.sample(f.varyings.*uvs, f.ddx.*uvs, f.ddy.*uvs, sampler));
  const glm::vec3 m = texel * 2.0f - 1.0f;
  const glm::vec3 mapped = t * (frame_scale * m.x * scale) + b * (frame_scale * m.y * scale) + n * m.z;
  const float length = glm::length(mapped);
  return length > 0.0f && std::isfinite(length) ? mapped / length : n;
}

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
  return apply_normal_map(t, b, n, 1.0f / std::sqrt(extent), f, map, sampler, scale, uvs);
}

// The frame of the mesh's tangent (glTF 2.0, "Meshes": bitangent = cross(normal, tangent.xyz) * tangent.w), made
// orthogonal to n by Gram-Schmidt. n is the unit normal of the side shown, `side` -1 on a back face: there the
// whole frame turns over, as three.js turns it. Where the tangent is zero or along n (no tangent for this vertex),
// the cotangent frame above.
template <class V>
glm::vec3 tangent_mapped_normal(glm::vec3 n, glm::vec4 tangent, float side, const Fragment<V>& f, const Texture& map,
                                const Sampler& sampler, float scale, glm::vec2 V::*uvs = &V::uv) {
  glm::vec3 t = side * glm::vec3(tangent);
  t -= n * glm::dot(n, t);
  const float t_length = glm::length(t);
  if (!(t_length > 1e-6f) || !std::isfinite(t_length)) return mapped_normal(n, f, map, sampler, scale, uvs);
  t /= t_length;
  const glm::vec3 b = glm::cross(n, t) * (side * (tangent.w < 0.0f ? -1.0f : 1.0f));
  return apply_normal_map(t, b, n, 1.0f, f, map, sampler, scale, uvs);  // 1 * x is x: the same rounding as without
}

}  // namespace facet
