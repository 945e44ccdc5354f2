// octahedral_map.hpp - a float RGB map over the sphere in octahedral layout, the storage of prefiltered light.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

namespace facet::detail {

// The sphere folded onto a square (Engelhardt and Dachsbacher, "Octahedron Environment Maps", 2008): the upper
// hemisphere (+Y) is the diamond at the centre, the lower one the four corners. A direction maps with one division
// and no trigonometry, so a lookup costs little more than a bilinear texture fetch.
inline glm::vec2 octahedral_from_direction(glm::vec3 d) {
  const float s = std::abs(d.x) + std::abs(d.y) + std::abs(d.z);
  float px = d.x / s, pz = d.z / s;
  if (d.y < 0.0f) {
    const float fx = (1.0f - std::abs(pz)) * (px < 0.0f ? -1.0f : 1.0f);
    const float fz = (1.0f - std::abs(px)) * (pz < 0.0f ? -1.0f : 1.0f);
    px = fx, pz = fz;
  }
  return {px * 0.5f + 0.5f, pz * 0.5f + 0.5f};
}

inline glm::vec3 direction_from_octahedral(glm::vec2 uv) {
  float px = uv.x * 2.0f - 1.0f, pz = uv.y * 2.0f - 1.0f;
  const float y = 1.0f - std::abs(px) - std::abs(pz);
  if (y < 0.0f) {
    const float fx = (1.0f - std::abs(pz)) * (px < 0.0f ? -1.0f : 1.0f);
    const float fz = (1.0f - std::abs(px)) * (pz < 0.0f ? -1.0f : 1.0f);
    px = fx, pz = fz;
  }
  return glm::normalize(glm::vec3(px, y, pz));
}

class OctahedralMap {
 public:
  OctahedralMap() = default;
  explicit OctahedralMap(int size)
      : size_(size), texels_(static_cast<std::size_t>(size) * static_cast<std::size_t>(size)) {}

  int size() const { return size_; }
  const glm::vec4* texels() const { return texels_.data(); }  // row-major, size() x size()

  // Sets every texel to f(direction of its centre).
  template <class F>
  void fill(F f) {
    fill_rows(0, size_, f);
  }
  // The same for rows [y0, y1) only: disjoint ranges may be filled on different threads.
  template <class F>
  void fill_rows(int y0, int y1, F f) {
    for (int y = y0; y < y1; ++y)
      for (int x = 0; x < size_; ++x) {
        const glm::vec2 uv((static_cast<float>(x) + 0.5f) / static_cast<float>(size_),
                           (static_cast<float>(y) + 0.5f) / static_cast<float>(size_));
        texels_[index(x, y)] = glm::vec4(f(direction_from_octahedral(uv)), 0.0f);
      }
  }

  // The map at half the size, each texel the mean of the 2x2 it covers (a box-filtered mip level).
  OctahedralMap half() const {
    OctahedralMap out(std::max(1, size_ / 2));
    for (int y = 0; y < out.size_; ++y)
      for (int x = 0; x < out.size_; ++x) {
        const int x1 = std::min(2 * x + 1, size_ - 1), y1 = std::min(2 * y + 1, size_ - 1);
        out.texels_[out.index(x, y)] = (texels_[index(2 * x, 2 * y)] + texels_[index(x1, 2 * y)] +
                                        texels_[index(2 * x, y1)] + texels_[index(x1, y1)]) *
                                       0.25f;
      }
    return out;
  }

  // Bilinear lookup along unit direction d, clamped at the square's edges.
  glm::vec3 sample(glm::vec3 d) const { return sample(octahedral_from_direction(d)); }
  // The same at the map's coordinates uv (octahedral_from_direction).
  glm::vec3 sample(glm::vec2 uv) const {
    const float n = static_cast<float>(size_);
    // Clamped to [0, n - 1], NaN (from a degenerate direction) to 0, so that every index is in range.
    const auto coordinate = [n](float v) {
      const float c = v * n - 0.5f;
      return c > 0.0f ? (c < n - 1.0f ? c : n - 1.0f) : 0.0f;
    };
    const float s = coordinate(uv.x), t = coordinate(uv.y);
    const int i = static_cast<int>(s), j = static_cast<int>(t);
    const int i1 = std::min(i + 1, size_ - 1), j1 = std::min(j + 1, size_ - 1);
    const float a = s - static_cast<float>(i), b = t - static_cast<float>(j);
    const glm::vec4 bottom = texels_[index(i, j)] + (texels_[index(i1, j)] - texels_[index(i, j)]) * a;
    const glm::vec4 top = texels_[index(i, j1)] + (texels_[index(i1, j1)] - texels_[index(i, j1)]) * a;
    return glm::vec3(bottom + (top - bottom) * b);
  }

 private:
  std::size_t index(int x, int y) const {
    return static_cast<std::size_t>(y) * static_cast<std::size_t>(size_) + static_cast<std::size_t>(x);
  }
  int size_ = 0;
  std::vector<glm::vec4> texels_;  // rgb and padding, so that a texel is one 16-byte load
};

}  // namespace facet::detail
