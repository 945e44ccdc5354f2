// surface.hpp - SurfaceShader: per-pixel Phong or Blinn-Phong lighting of a textured, vertex-coloured material.
#pragma once

#include <algorithm>
#include <cmath>

#include "facet/shaders/lit.hpp"

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

  // A tangent-space normal map, or null; its frame comes from the screen-space derivatives of the world position
  // and the uvs (a cotangent frame, as in Schueler's "Normal Mapping without Precomputed Tangents"), so meshes need
  // no tangents.
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

  glm::vec3 mapped_normal(glm::vec3 n, const Fragment<Varyings>& f) const {
    // Window y grows downwards; the frame is built for y up, as OpenGL's dFdy gives it.
    const glm::vec3 dp1 = f.ddx.world, dp2 = -f.ddy.world;
    const glm::vec2 duv1 = f.ddx.uv, duv2 = -f.ddy.uv;
    const glm::vec3 dp2perp = glm::cross(dp2, n), dp1perp = glm::cross(n, dp1);
    const glm::vec3 t = dp2perp * duv1.x + dp1perp * duv2.x, b = dp2perp * duv1.y + dp1perp * duv2.y;
    const float extent = std::max(glm::dot(t, t), glm::dot(b, b));
    if (!(extent > 0.0f) || !std::isfinite(extent)) return n;  // uvs constant over the pixel: no frame
    const float scale = 1.0f / std::sqrt(extent);
    const glm::vec3 texel = glm::vec3(normal_map->sample(f.varyings.uv, f.ddx.uv, f.ddy.uv, surface.sampler));
    const glm::vec3 m = texel * 2.0f - 1.0f;
    const glm::vec3 mapped = t * (scale * m.x * normal_scale) + b * (scale * m.y * normal_scale) + n * m.z;
    const float length = glm::length(mapped);
    return length > 0.0f && std::isfinite(length) ? mapped / length : n;
  }
};

}  // namespace facet
