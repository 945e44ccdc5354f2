// position_key.hpp - vertex positions as hash keys, for the normal computations that group vertices by position.
#pragma once

#include <cstdint>

#include <glm/vec3.hpp>

#include "facet/detail/bits.hpp"

namespace facet::detail {

// Positions compare by value, as the benchmark's reference renderer does (BENCHMARK.md 8.3), so -0 and +0 are one key.
struct PositionKey {
  std::uint32_t bits[3];
  explicit PositionKey(const glm::vec3& p) {
    for (int k = 0; k < 3; ++k) bits[k] = detail::bit_cast<std::uint32_t>(p[k] == 0.0f ? 0.0f : p[k]);
  }
  bool operator==(const PositionKey& o) const {
    return bits[0] == o.bits[0] && bits[1] == o.bits[1] && bits[2] == o.bits[2];
  }
};

inline std::uint64_t position_hash(const PositionKey& k) {
  std::uint64_t h = 0x9e3779b97f4a7c15ull;
  for (std::uint32_t b : k.bits) h = (h ^ b) * 0x100000001b3ull;
  return h ^ (h >> 29);
}

}  // namespace facet::detail
