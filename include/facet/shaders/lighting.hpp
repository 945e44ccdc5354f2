// lighting.hpp - a fixed-size light block and the ambient + diffuse + specular model the lit shaders share.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>

#include <glm/glm.hpp>

namespace facet {

inline constexpr int kLightSlots = 4;  // fixed so a shader's uniforms stay a plain, allocation-free struct

// Lights in world space. Colours already include the intensity.
struct LightBlock {
  int count = 0;
  std::array<glm::vec4, kLightSlots> vector_kind{};  // xyz: direction towards the light (w = 0) or position (w = 1)
  std::array<glm::vec3, kLightSlots> color{};
  glm::vec3 ambient{0.0f};

  // Both return false (and add nothing) when the block is full.
  bool add_directional(glm::vec3 towards_light, glm::vec3 light_color) {
    if (count >= kLightSlots) return false;
    vector_kind[count] = glm::vec4(glm::normalize(towards_light), 0.0f);
    color[count++] = light_color;
    return true;
  }
  bool add_point(glm::vec3 position, glm::vec3 light_color) {
    if (count >= kLightSlots) return false;
    vector_kind[count] = glm::vec4(position, 1.0f);
    color[count++] = light_color;
    return true;
  }
};

enum class SpecularModel {
  phong,        // pow(max(dot(reflect(-L, N), V), 0), shininess)
  blinn_phong,  // pow(max(dot(N, normalize(L + V)), 0), shininess)
};

// What the lights contribute at one point: `diffuse` (ambient included) scales the albedo, `specular` scales the
// material's specular colour. Kept apart so Gouraud shading can interpolate both and apply the albedo per pixel.
struct LightTerms {
  glm::vec3 diffuse{0.0f};
  glm::vec3 specular{0.0f};
};

// n must be unit length; to_eye need not be. As in the reference shader (BENCHMARK.md section 7) the specular term is
// not gated by dot(N, L) and back-facing normals are not flipped, so back faces get the same formula as in OpenGL.
// Point lights have no attenuation. with_specular = false skips the pow() where the specular colour is black.
inline LightTerms light_terms(const LightBlock& lights, glm::vec3 n, glm::vec3 position, glm::vec3 to_eye,
                              float shininess, SpecularModel model, bool with_specular = true) {
  LightTerms terms{lights.ambient, glm::vec3(0.0f)};
  const glm::vec3 v = glm::normalize(to_eye);
  for (int i = 0; i < lights.count; ++i) {
    const glm::vec4 vk = lights.vector_kind[static_cast<std::size_t>(i)];
    const glm::vec3 l = vk.w == 0.0f ? glm::vec3(vk) : glm::normalize(glm::vec3(vk) - position);
    const float n_dot_l = glm::dot(n, l);
    const glm::vec3 c = lights.color[static_cast<std::size_t>(i)];
    terms.diffuse += std::max(n_dot_l, 0.0f) * c;
    if (!with_specular) continue;
    float s;
    if (model == SpecularModel::phong) {
      const glm::vec3 r = -l + 2.0f * n_dot_l * n;
      s = glm::dot(r, v);
    } else {
      s = glm::dot(n, glm::normalize(l + v));
    }
    terms.specular += std::pow(std::max(s, 0.0f), shininess) * c;
  }
  return terms;
}

// The lit colour of a surface point: albedo * (ambient + diffuse) + specular colour * specular.
inline glm::vec3 shade_lit(const LightBlock& lights, glm::vec3 albedo, glm::vec3 specular, float shininess,
                           SpecularModel model, glm::vec3 n, glm::vec3 position, glm::vec3 to_eye) {
  const bool with_specular = specular != glm::vec3(0.0f);
  const LightTerms t = light_terms(lights, n, position, to_eye, shininess, model, with_specular);
  return albedo * t.diffuse + specular * t.specular;
}

}  // namespace facet
