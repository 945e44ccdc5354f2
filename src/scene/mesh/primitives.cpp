// primitives.cpp - procedural meshes: the coloured WebGL cube, a colour-swept torus, the benchmark sphere, a pentagon.
#include "facet/primitives.hpp"

#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

namespace facet {

namespace {

struct CubeFace {
  glm::vec3 corners[4];  // c0 c1 c2 c3, counter-clockwise from outside, in the post's order
  glm::vec3 color, normal, u_axis, v_axis;
};

// The six faces in the order of "Barebones 3D rendering with WebGL", which labels both y faces "BOTTOM"; the first
// one is really at +y.
constexpr CubeFace kCubeFaces[6] = {
    {{{-1, -1, 1}, {1, -1, 1}, {1, 1, 1}, {-1, 1, 1}}, {1, 0, 0}, {0, 0, 1}, {1, 0, 0}, {0, 1, 0}},
    {{{1, -1, -1}, {1, 1, -1}, {1, 1, 1}, {1, -1, 1}}, {0, 1, 0}, {1, 0, 0}, {0, 0, -1}, {0, 1, 0}},
    {{{1, -1, -1}, {-1, -1, -1}, {-1, 1, -1}, {1, 1, -1}}, {0, 0, 1}, {0, 0, -1}, {-1, 0, 0}, {0, 1, 0}},
    {{{-1, -1, -1}, {-1, -1, 1}, {-1, 1, 1}, {-1, 1, -1}}, {1, 1, 0}, {-1, 0, 0}, {0, 0, 1}, {0, 1, 0}},
    {{{1, 1, -1}, {-1, 1, -1}, {-1, 1, 1}, {1, 1, 1}}, {1, 0, 1}, {0, 1, 0}, {1, 0, 0}, {0, 0, -1}},
    {{{-1, -1, -1}, {1, -1, -1}, {1, -1, 1}, {-1, -1, 1}}, {0, 1, 1}, {0, -1, 0}, {1, 0, 0}, {0, 0, 1}},
};

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument(what);
}

// (rows + 1) * (columns + 1) vertices must be addressable with 32-bit indices.
void require_grid(long long rows, long long columns, const char* fn) {
  require((rows + 1) * (columns + 1) <= std::numeric_limits<std::uint32_t>::max(),
          std::string(fn) + ": too many segments for 32-bit indices");
}

}  // namespace

Mesh make_cube() {
  Mesh mesh;
  for (std::uint32_t f = 0; f < 6; ++f) {
    const CubeFace& face = kCubeFaces[f];
    const glm::vec4 color(face.color, 1.0f);
    for (const glm::vec3& c : face.corners) {
      mesh.positions.push_back(c);
      mesh.normals.push_back(face.normal);
      // The corner's coordinates along the face's right and up axes, -1..1, mapped to 0..1.
      mesh.uvs.push_back({(glm::dot(c, face.u_axis) + 1) * 0.5f, (glm::dot(c, face.v_axis) + 1) * 0.5f});
      mesh.colors.push_back(color);
    }
    const std::uint32_t b = 4 * f;
    mesh.indices.insert(mesh.indices.end(), {b, b + 1, b + 2, b, b + 2, b + 3});
    mesh.face_colors.insert(mesh.face_colors.end(), {color, color});
  }
  validate(mesh, "make_cube");
  return mesh;
}

std::vector<float> colored_cube_vertex_data() {
  // Verbatim from the vertexData of "Barebones 3D rendering with WebGL": pos = x, y, z, color = r, g, b.
  // clang-format off
  return {
      // FRONT
      -1, -1, 1, 1, 0, 0,   1, -1, 1, 1, 0, 0,    1, 1, 1, 1, 0, 0,
      -1, -1, 1, 1, 0, 0,   1, 1, 1, 1, 0, 0,     -1, 1, 1, 1, 0, 0,
      // RIGHT
      1, -1, -1, 0, 1, 0,   1, 1, -1, 0, 1, 0,    1, 1, 1, 0, 1, 0,
      1, -1, -1, 0, 1, 0,   1, 1, 1, 0, 1, 0,     1, -1, 1, 0, 1, 0,
      // BACK
      1, -1, -1, 0, 0, 1,   -1, -1, -1, 0, 0, 1,  -1, 1, -1, 0, 0, 1,
      1, -1, -1, 0, 0, 1,   -1, 1, -1, 0, 0, 1,   1, 1, -1, 0, 0, 1,
      // LEFT
      -1, -1, -1, 1, 1, 0,  -1, -1, 1, 1, 1, 0,   -1, 1, 1, 1, 1, 0,
      -1, -1, -1, 1, 1, 0,  -1, 1, 1, 1, 1, 0,    -1, 1, -1, 1, 1, 0,
      // "BOTTOM" in the post, at y = +1
      1, 1, -1, 1, 0, 1,    -1, 1, -1, 1, 0, 1,   -1, 1, 1, 1, 0, 1,
      1, 1, -1, 1, 0, 1,    -1, 1, 1, 1, 0, 1,    1, 1, 1, 1, 0, 1,
      // BOTTOM
      -1, -1, -1, 0, 1, 1,  1, -1, -1, 0, 1, 1,   1, -1, 1, 0, 1, 1,
      -1, -1, -1, 0, 1, 1,  1, -1, 1, 0, 1, 1,    -1, -1, 1, 0, 1, 1,
  };
  // clang-format on
}

Mesh make_torus(float major_radius, float minor_radius, int major_segments, int minor_segments) {
  require(std::isfinite(major_radius) && major_radius > 0 && std::isfinite(minor_radius) && minor_radius > 0,
          "make_torus: radii must be finite and positive");
  require(major_segments >= 3 && minor_segments >= 3, "make_torus: at least 3 segments each way");
  require_grid(major_segments, minor_segments, "make_torus");
  const double two_pi = 2 * std::numbers::pi;
  const std::uint32_t columns = static_cast<std::uint32_t>(minor_segments) + 1;
  Mesh mesh;
  for (int i = 0; i <= major_segments; ++i) {
    // The closing ring and column reuse index 0's angle so the seams weld bit for bit.
    const double u = two_pi * (i == major_segments ? 0 : i) / major_segments;
    const float t = static_cast<float>(i) / static_cast<float>(major_segments);
    for (int j = 0; j <= minor_segments; ++j) {
      const double v = two_pi * (j == minor_segments ? 0 : j) / minor_segments;
      const glm::dvec3 n(std::cos(v) * std::cos(u), std::cos(v) * std::sin(u), std::sin(v));
      const glm::dvec3 centre(major_radius * std::cos(u), major_radius * std::sin(u), 0.0);
      mesh.positions.push_back(glm::vec3(centre + static_cast<double>(minor_radius) * n));
      mesh.normals.push_back(glm::vec3(n));
      mesh.uvs.push_back({t, static_cast<float>(j) / static_cast<float>(minor_segments)});
      mesh.colors.push_back({t, 0.0f, 1.0f - t, 1.0f});
    }
  }
  for (std::uint32_t i = 0; i < static_cast<std::uint32_t>(major_segments); ++i)
    for (std::uint32_t j = 0; j < static_cast<std::uint32_t>(minor_segments); ++j) {
      // a -> b goes around the major circle, a -> a+1 around the tube; this order faces outwards.
      const std::uint32_t a = i * columns + j, b = a + columns;
      mesh.indices.insert(mesh.indices.end(), {a, b, b + 1, a, b + 1, a + 1});
    }
  validate(mesh, "make_torus");
  return mesh;
}

Mesh make_uv_sphere(int stacks, int slices, glm::vec2 uv_repeat) {
  require(stacks >= 2 && slices >= 3, "make_uv_sphere: need stacks >= 2 and slices >= 3");
  require_grid(stacks, slices, "make_uv_sphere");
  // Float arithmetic in exactly the reference's order (BENCHMARK.md 8.1), so sphere:N matches it bit for bit.
  const float pi = std::numbers::pi_v<float>;
  Mesh mesh;
  for (int i = 0; i <= stacks; ++i) {
    const float theta = pi * static_cast<float>(i) / static_cast<float>(stacks);
    for (int j = 0; j <= slices; ++j) {
      const float phi = 2.0f * pi * static_cast<float>(j) / static_cast<float>(slices);
      const glm::vec3 n(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
      mesh.positions.push_back(n);
      mesh.normals.push_back(n);
      mesh.uvs.push_back({uv_repeat.x * static_cast<float>(j) / static_cast<float>(slices),
                          uv_repeat.y * static_cast<float>(i) / static_cast<float>(stacks)});
    }
  }
  const std::uint32_t row = static_cast<std::uint32_t>(slices) + 1;
  for (std::uint32_t i = 0; i < static_cast<std::uint32_t>(stacks); ++i)
    for (std::uint32_t j = 0; j < static_cast<std::uint32_t>(slices); ++j) {
      const std::uint32_t a = i * row + j, b = a + row;
      // The pole rows keep only their non-degenerate triangle.
      if (i != 0) mesh.indices.insert(mesh.indices.end(), {a, a + 1, b});
      if (i + 1 != static_cast<std::uint32_t>(stacks)) mesh.indices.insert(mesh.indices.end(), {a + 1, b + 1, b});
    }
  validate(mesh, "make_uv_sphere");
  return mesh;
}

Mesh make_pentagon() {
  static constexpr glm::vec4 kColors[5] = {{1, 0, 0, 1}, {1, 1, 0, 1}, {0, 1, 0, 1}, {0, 0, 1, 1}, {1, 0, 1, 1}};
  Mesh mesh;
  for (int k = 0; k < 5; ++k) {
    const double a = std::numbers::pi / 2 + 2 * std::numbers::pi * k / 5;
    const glm::vec3 p(static_cast<float>(std::cos(a)), static_cast<float>(std::sin(a)), 0.0f);
    mesh.positions.push_back(p);
    mesh.normals.push_back({0, 0, 1});
    mesh.uvs.push_back({0.5f + 0.5f * p.x, 0.5f + 0.5f * p.y});
    mesh.colors.push_back(kColors[k]);
  }
  const std::uint32_t fan[5] = {0, 1, 2, 3, 4};
  mesh.indices = triangles_from_fan(fan);
  validate(mesh, "make_pentagon");
  return mesh;
}

}  // namespace facet
