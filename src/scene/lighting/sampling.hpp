// sampling.hpp - low-discrepancy sample points for the numerical integrals of prefiltering.
#pragma once

#include <cstdint>

#include <glm/glm.hpp>

#include "facet/detail/octahedral_map.hpp"

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

}  // namespace facet
