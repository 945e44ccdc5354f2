// scenes.hpp - geometry the rasterization tests share: jittered grids, closed spheres, random triangle soups.
#pragma once

#include <cstdint>
#include <random>
#include <vector>

#include <glm/glm.hpp>

namespace facet::test {

struct ClipMesh {
  std::vector<glm::vec4> clip;
  std::vector<glm::vec3> color;
  std::vector<std::uint32_t> indices;
};

// (cells_x + 1) x (cells_y + 1) points spanning NDC [-1, 1]^2, interior points jittered by up to 0.3 cell
// (small enough that every cell stays convex, so its two triangles never fold over each other), two
// triangles per cell with alternating diagonals. Each vertex gets a random w in [0.5, 4] (the same NDC point).
inline ClipMesh jittered_grid(int cells_x, int cells_y, std::uint32_t seed, bool random_w) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> jitter(-0.3f, 0.3f), weight(0.5f, 4.0f), hue(0.0f, 1.0f);
  ClipMesh m;
  for (int j = 0; j <= cells_y; ++j)
    for (int i = 0; i <= cells_x; ++i) {
      float x = static_cast<float>(i), y = static_cast<float>(j);
      if (i > 0 && i < cells_x) x += jitter(rng);
      if (j > 0 && j < cells_y) y += jitter(rng);
      const float w = random_w ? weight(rng) : 1.0f;
      const glm::vec2 ndc(2.0f * x / cells_x - 1.0f, 2.0f * y / cells_y - 1.0f);
      m.clip.emplace_back(ndc.x * w, ndc.y * w, 0.0f, w);
      m.color.emplace_back(hue(rng), hue(rng), hue(rng));
    }
  const auto at = [&](int i, int j) { return static_cast<std::uint32_t>(j * (cells_x + 1) + i); };
  for (int j = 0; j < cells_y; ++j)
    for (int i = 0; i < cells_x; ++i) {
      const std::uint32_t a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
      if ((i + j) % 2) m.indices.insert(m.indices.end(), {a, b, c, a, c, d});
      else m.indices.insert(m.indices.end(), {a, b, d, b, c, d});
    }
  return m;
}

// A closed unit UV sphere (the seam and the poles share vertices), transformed to clip space.
inline ClipMesh closed_sphere(int stacks, int slices, const glm::mat4& clip_from_object) {
  ClipMesh m;
  const float pi = 3.14159265358979f;
  m.clip.push_back(clip_from_object * glm::vec4(0, 1, 0, 1));
  m.color.emplace_back(1, 1, 1);
  for (int i = 1; i < stacks; ++i)
    for (int j = 0; j < slices; ++j) {
      const float theta = pi * i / stacks, phi = 2 * pi * j / slices;
      const glm::vec3 p(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
      m.clip.push_back(clip_from_object * glm::vec4(p, 1));
      m.color.push_back(0.5f * p + 0.5f);
    }
  m.clip.push_back(clip_from_object * glm::vec4(0, -1, 0, 1));
  m.color.emplace_back(0, 0, 0);
  const auto ring = [&](int i, int j) { return static_cast<std::uint32_t>(1 + (i - 1) * slices + (j % slices)); };
  const auto bottom = static_cast<std::uint32_t>(m.clip.size() - 1);
  for (int j = 0; j < slices; ++j) m.indices.insert(m.indices.end(), {0, ring(1, j + 1), ring(1, j)});
  for (int i = 1; i + 1 < stacks; ++i)
    for (int j = 0; j < slices; ++j)
      m.indices.insert(m.indices.end(), {ring(i, j), ring(i, j + 1), ring(i + 1, j), ring(i, j + 1), ring(i + 1, j + 1),
                                         ring(i + 1, j)});
  for (int j = 0; j < slices; ++j)
    m.indices.insert(m.indices.end(), {ring(stacks - 1, j), ring(stacks - 1, j + 1), bottom});
  return m;
}

// Random triangles in and around the view volume, some crossing the near plane or lying behind the eye.
inline ClipMesh triangle_soup(int count, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> xy(-1.6f, 1.6f), z(-1.3f, 1.3f), w(-0.3f, 3.0f), hue(0.0f, 1.0f);
  ClipMesh m;
  for (int t = 0; t < count; ++t) {
    const float wt = std::max(w(rng), 0.2f);
    for (int k = 0; k < 3; ++k) {
      const float wk = k == 2 && t % 7 == 0 ? -0.5f : wt + 0.3f * k;  // every 7th crosses behind the eye
      m.clip.emplace_back(xy(rng) * wk, xy(rng) * wk, z(rng) * std::abs(wk), wk);
      m.color.emplace_back(hue(rng), hue(rng), hue(rng));
      m.indices.push_back(static_cast<std::uint32_t>(m.clip.size() - 1));
    }
  }
  return m;
}

}  // namespace facet::test
