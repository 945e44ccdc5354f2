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

constexpr int kSamples = 64;

// The GGX-distributed half vectors of one roughness, around the normal (0, 0, 1): the same for every NdotV of a
// row of the table, so their trigonometry is taken once per row.
using HalfVectors = std::array<glm::vec3, kSamples>;

HalfVectors half_vectors(float alpha) {
  // The samples' azimuths, the same for every roughness.
  static const std::array<glm::vec2, kSamples> azimuths = [] {
    std::array<glm::vec2, kSamples> out{};
    for (int i = 0; i < kSamples; ++i) {
      const float phi = 2.0f * brdf::kPi * hammersley(i, kSamples).x;
      out[static_cast<std::size_t>(i)] = {std::cos(phi), std::sin(phi)};
    }
    return out;
  }();
  HalfVectors h{};
  for (int i = 0; i < kSamples; ++i) {
    const float xi = hammersley(i, kSamples).y;
    const float cos_theta = std::sqrt((1.0f - xi) / (1.0f + (alpha * alpha - 1.0f) * xi));
    const float sin_theta = std::sqrt(std::max(0.0f, 1.0f - cos_theta * cos_theta));
    const glm::vec2 azimuth = azimuths[static_cast<std::size_t>(i)];
    h[static_cast<std::size_t>(i)] = glm::vec3(sin_theta * azimuth.x, sin_theta * azimuth.y, cos_theta);
  }
  return h;
}

// For v at NdotV from the normal (0, 0, 1): the integral over l of the BRDF times NdotL with F = f0 A + f90 B,
// estimated with GGX-distributed half vectors (pdf of l = D NdotH / (4 VdotH)), so that each sample contributes
// V 4 NdotL VdotH / NdotH, split by the Fresnel weight (1 - VdotH)^5 into A's and B's part.
glm::vec2 integrate(float n_dot_v, float alpha, const HalfVectors& half) {
  const glm::vec3 v(std::sqrt(1.0f - n_dot_v * n_dot_v), 0.0f, n_dot_v);
  glm::vec2 sum(0.0f);
  for (const glm::vec3& h : half) {
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
    for (int j = 0; j < kBrdfTableSize; ++j) {
      const float roughness = (static_cast<float>(j) + 0.5f) / kBrdfTableSize;
      const float alpha = roughness * roughness;
      // Aligned to a cache line: at some stack addresses the unaligned array's reads took 2.5 times as long.
      alignas(64) const HalfVectors half = half_vectors(alpha);
      for (int i = 0; i < kBrdfTableSize; ++i) {
        const float n_dot_v = (static_cast<float>(i) + 0.5f) / kBrdfTableSize;
        out[static_cast<std::size_t>(j * kBrdfTableSize + i)] = integrate(n_dot_v, alpha, half);
      }
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
