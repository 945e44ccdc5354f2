// brdf_table.hpp - the split-sum table's layout and its bilinear lookup, inline for the shaders' inner loops.
#pragma once

#include <glm/glm.hpp>

namespace facet {

inline constexpr int kBrdfTableSize = 32;

namespace detail {

// kBrdfTableSize^2 entries (A, B), NdotV along rows, roughness down columns, at texel centres (i + 0.5) / size.
const glm::vec2* brdf_table_entries();

inline glm::vec2 brdf_table_lookup(const glm::vec2* table, float n_dot_v, float roughness) {
  constexpr float n = kBrdfTableSize;
  const auto coordinate = [](float v) {
    const float c = v * n - 0.5f;
    return c > 0.0f ? (c < n - 1.0f ? c : n - 1.0f) : 0.0f;  // NaN to 0
  };
  const float s = coordinate(n_dot_v), r = coordinate(roughness);
  const int i = static_cast<int>(s), j = static_cast<int>(r);
  const int i1 = i + 1 < kBrdfTableSize ? i + 1 : i, j1 = j + 1 < kBrdfTableSize ? j + 1 : j;
  const float a = s - static_cast<float>(i), b = r - static_cast<float>(j);
  const glm::vec2 t00 = table[j * kBrdfTableSize + i], t10 = table[j * kBrdfTableSize + i1];
  const glm::vec2 t01 = table[j1 * kBrdfTableSize + i], t11 = table[j1 * kBrdfTableSize + i1];
  const glm::vec2 bottom = t00 + (t10 - t00) * a;
  const glm::vec2 top = t01 + (t11 - t01) * a;
  return bottom + (top - bottom) * b;
}

}  // namespace detail
}  // namespace facet
