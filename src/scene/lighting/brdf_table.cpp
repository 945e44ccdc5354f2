// brdf_table.cpp - the split-sum table of the GGX specular BRDF's directional albedo, integrated once.
#include <algorithm>
#include <array>
#include <cmath>

#include "facet/environment.hpp"
#include "facet/shaders/brdf.hpp"
#include "scene/lighting/sampling.hpp"

namespace facet {

namespace {

using Table = std::array<glm::vec2, kBrdfTableSize * kBrdfTableSize>;

// For v at NdotV from the normal (0, 0, 1): the integral over l of the BRDF times NdotL with F = f0 A + f90 B,
// estimated with GGX-distributed half vectors (pdf of l = D NdotH / (4 VdotH)), so that each sample contributes
// V 4 NdotL VdotH / NdotH, split by the Fresnel weight (1 - VdotH)^5 into A's and B's part.
glm::vec2 integrate(float n_dot_v, float roughness) {
  constexpr int kSamples = 64;
  const float alpha = roughness * roughness;
  const glm::vec3 v(std::sqrt(1.0f - n_dot_v * n_dot_v), 0.0f, n_dot_v);
  glm::vec2 sum(0.0f);
  for (int i = 0; i < kSamples; ++i) {
    const glm::vec2 xi = hammersley(i, kSamples);
    const float phi = 2.0f * brdf::kPi * xi.x;
    const float cos_theta = std::sqrt((1.0f - xi.y) / (1.0f + (alpha * alpha - 1.0f) * xi.y));
    const float sin_theta = std::sqrt(std::max(0.0f, 1.0f - cos_theta * cos_theta));
    const glm::vec3 h(sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta);
    const float v_dot_h = glm::dot(v, h);
    const glm::vec3 l = 2.0f * v_dot_h * h - v;
    if (l.z <= 0.0f || v_dot_h <= 0.0f) continue;
    const float vis = brdf::visibility_smith_ggx(l.z, n_dot_v, alpha);
    const float g = vis * 4.0f * l.z * v_dot_h / h.z;
    const float fc = brdf::schlick_weight(v_dot_h);
    sum += glm::vec2((1.0f - fc) * g, fc * g);
  }
  return sum / static_cast<float>(kSamples);
}

const Table& table() {
  static const Table t = [] {
    Table out{};
    for (int j = 0; j < kBrdfTableSize; ++j)
      for (int i = 0; i < kBrdfTableSize; ++i) {
        const float n_dot_v = (static_cast<float>(i) + 0.5f) / kBrdfTableSize;
        const float roughness = (static_cast<float>(j) + 0.5f) / kBrdfTableSize;
        out[static_cast<std::size_t>(j * kBrdfTableSize + i)] = integrate(n_dot_v, roughness);
      }
    return out;
  }();
  return t;
}

}  // namespace

const glm::vec2* detail::brdf_table_entries() { return table().data(); }

glm::vec2 brdf_table(float n_dot_v, float roughness) {
  return detail::brdf_table_lookup(table().data(), n_dot_v, roughness);
}

}  // namespace facet
