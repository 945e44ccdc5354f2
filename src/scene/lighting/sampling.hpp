// sampling.hpp - sample points for the numerical integrals of prefiltering: low-discrepancy sets, equirect columns.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "facet/detail/octahedral_map.hpp"
#include "facet/shaders/brdf.hpp"

namespace facet {

using detail::OctahedralMap;

// Point i of the n-point Hammersley set in [0, 1)^2: (i / n, the radical inverse of i in base 2).
inline glm::vec2 hammersley(int i, int n) {
  std::uint32_t bits = static_cast<std::uint32_t>(i);
  bits = (bits << 16u) | (bits >> 16u);
  bits = ((bits & 0x55555555u) << 1u) | ((bits & 0xAAAAAAAAu) >> 1u);
  bits = ((bits & 0x33333333u) << 2u) | ((bits & 0xCCCCCCCCu) >> 2u);
  bits = ((bits & 0x0F0F0F0Fu) << 4u) | ((bits & 0xF0F0F0F0u) >> 4u);
  bits = ((bits & 0x00FF00FFu) << 8u) | ((bits & 0xFF00FF00u) >> 8u);
  return {static_cast<float>(i) / static_cast<float>(n), static_cast<float>(bits) * 2.3283064365386963e-10f};
}

// The cosine and sine of each column's azimuth in an equirectangular image `width` texels wide (column x at
// phi = 2 pi ((x + 0.5) / width - 0.5)): taken once per column rather than once per texel.
struct ColumnAzimuths {
  std::vector<float> cos, sin;
};
inline ColumnAzimuths column_azimuths(int width) {
  const std::size_t columns = static_cast<std::size_t>(width);
  ColumnAzimuths out{std::vector<float>(columns), std::vector<float>(columns)};
  for (int x = 0; x < width; ++x) {
    const float phi = 2.0f * brdf::kPi * ((static_cast<float>(x) + 0.5f) / static_cast<float>(width) - 0.5f);
    out.cos[static_cast<std::size_t>(x)] = std::cos(phi);
    out.sin[static_cast<std::size_t>(x)] = std::sin(phi);
  }
  return out;
}

}  // namespace facet
