// test_primitives.cpp - unit tests for primitives.hpp: counts, orientation, closedness and attributes of each shape.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <numbers>
#include <set>
#include <stdexcept>
#include <tuple>

#include "facet/mesh.hpp"
#include "facet/primitives.hpp"

namespace facet::primitives_tests {
namespace {

glm::vec3 corner(const Mesh& m, std::size_t t, int c) {
  return m.positions[m.indices[3 * t + static_cast<std::size_t>(c)]];
}

glm::vec3 face_normal(const Mesh& m, std::size_t t) {
  return glm::cross(corner(m, t, 1) - corner(m, t, 0), corner(m, t, 2) - corner(m, t, 0));
}

double signed_volume(const Mesh& m) {
  double v = 0;
  for (std::size_t t = 0; t < m.triangle_count(); ++t)
    v += glm::dot(glm::dvec3(corner(m, t, 0)), glm::cross(glm::dvec3(corner(m, t, 1)), glm::dvec3(corner(m, t, 2)))) /
         6.0;
  return v;
}

// Welds vertices whose positions agree to 1e-5 (the sphere's seam differs in the last bits), then counts directed
// edges. Closed and consistently oriented: every edge is used once in each direction and by no other triangle.
// Returns the number of boundary edges (used once), or -1 if some edge is used in a way a closed surface cannot.
int boundary_edges(const Mesh& m) {
  std::map<std::tuple<long, long, long>, std::uint32_t> weld;
  std::vector<std::uint32_t> id(m.vertex_count());
  for (std::size_t v = 0; v < m.vertex_count(); ++v) {
    const glm::vec3 p = m.positions[v] * 1e5f;
    id[v] = weld.try_emplace({std::lround(p.x), std::lround(p.y), std::lround(p.z)},
                             static_cast<std::uint32_t>(weld.size()))
                .first->second;
  }
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
  for (std::size_t i = 0; i < m.indices.size(); i += 3)
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = id[m.indices[i + static_cast<std::size_t>(k)]];
      const std::uint32_t b = id[m.indices[i + static_cast<std::size_t>((k + 1) % 3)]];
      if (a == b) return -1;  // a triangle collapsed by welding
      ++directed[{a, b}];
    }
  int boundary = 0;
  for (const auto& [edge, count] : directed) {
    if (count != 1) return -1;
    if (!directed.count({edge.second, edge.first})) ++boundary;
  }
  return boundary;
}

TEST(PrimitiveCube, MatchesTheColoredCubeVertexData) {
  const Mesh c = make_cube();
  EXPECT_EQ(c.vertex_count(), 24u);
  EXPECT_EQ(c.triangle_count(), 12u);
  ASSERT_EQ(c.face_colors.size(), 12u);
  const glm::vec4 expected_colors[6] = {{1, 0, 0, 1}, {0, 1, 0, 1}, {0, 0, 1, 1},
                                        {1, 1, 0, 1}, {1, 0, 1, 1}, {0, 1, 1, 1}};
  const glm::vec3 expected_normals[6] = {{0, 0, 1}, {1, 0, 0}, {0, 0, -1}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}};
  for (std::size_t t = 0; t < 12; ++t) {
    EXPECT_EQ(c.face_colors[t], expected_colors[t / 2]) << "triangle " << t;
    EXPECT_EQ(glm::normalize(face_normal(c, t)), expected_normals[t / 2]) << "triangle " << t;
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t v = c.indices[3 * t + static_cast<std::size_t>(k)];
      EXPECT_EQ(c.colors[v], expected_colors[t / 2]);
      EXPECT_EQ(c.normals[v], expected_normals[t / 2]);
    }
  }
  // Same triangles, corner for corner, as the post's interleaved buffer.
  const std::vector<float> buffer = colored_cube_vertex_data();
  for (std::size_t k = 0; k < 36; ++k)
    EXPECT_EQ(c.positions[c.indices[k]], glm::vec3(buffer[6 * k], buffer[6 * k + 1], buffer[6 * k + 2])) << k;
  EXPECT_EQ(boundary_edges(c), 0);
  EXPECT_NEAR(signed_volume(c), 8.0, 1e-9);
  const Bounds b = bounds(c);
  EXPECT_EQ(b.min, glm::vec3(-1));
  EXPECT_EQ(b.max, glm::vec3(1));
}

TEST(PrimitiveCube, UvsSpanEachFaceUpright) {
  const Mesh c = make_cube();
  for (std::size_t f = 0; f < 6; ++f) {
    std::set<std::pair<float, float>> uvs;
    for (std::size_t k = 0; k < 4; ++k) uvs.insert({c.uvs[4 * f + k].x, c.uvs[4 * f + k].y});
    EXPECT_EQ(uvs, (std::set<std::pair<float, float>>{{0, 0}, {1, 0}, {1, 1}, {0, 1}})) << "face " << f;
    // u grows to the right and v upwards seen from outside, so the uv winding matches the face's CCW winding.
    const glm::vec2 a = c.uvs[4 * f], b = c.uvs[4 * f + 1], d = c.uvs[4 * f + 2];
    EXPECT_GT((b.x - a.x) * (d.y - a.y) - (b.y - a.y) * (d.x - a.x), 0) << "face " << f;
  }
  // Side faces: v follows +y.
  for (std::size_t f = 0; f < 4; ++f)
    for (std::size_t k = 0; k < 4; ++k) EXPECT_EQ(c.uvs[4 * f + k].y, (c.positions[4 * f + k].y + 1) / 2);
}

TEST(PrimitiveTorus, CountsClosednessAndOrientation) {
  const float R = 1.0f, r = 0.25f;
  const int M = 40, N = 16;
  const Mesh t = make_torus(R, r, M, N);
  EXPECT_EQ(t.vertex_count(), static_cast<std::size_t>((M + 1) * (N + 1)));
  EXPECT_EQ(t.triangle_count(), static_cast<std::size_t>(2 * M * N));
  EXPECT_EQ(t.normals.size(), t.vertex_count());
  EXPECT_EQ(t.uvs.size(), t.vertex_count());
  EXPECT_EQ(t.colors.size(), t.vertex_count());
  EXPECT_EQ(boundary_edges(t), 0);
  // Volume of a torus is 2 pi^2 R r^2; the polygonal one is a little smaller.
  const double exact = 2 * std::numbers::pi * std::numbers::pi * R * r * r;
  EXPECT_NEAR(signed_volume(t), exact, 0.05 * exact);
  for (std::size_t i = 0; i < t.triangle_count(); ++i) {
    const glm::vec3 n = face_normal(t, i);
    for (int k = 0; k < 3; ++k) EXPECT_GT(glm::dot(n, t.normals[t.indices[3 * i + static_cast<std::size_t>(k)]]), 0);
  }
  for (std::size_t v = 0; v < t.vertex_count(); ++v) {
    const glm::vec3 p = t.positions[v];
    const glm::vec3 centre = R * glm::normalize(glm::vec3(p.x, p.y, 0));
    EXPECT_NEAR(glm::distance(p, centre), r, 1e-5f);
    EXPECT_NEAR(glm::distance(t.normals[v], (p - centre) / r), 0.0f, 1e-4f);
  }
  // Seams repeat positions bit for bit.
  for (int j = 0; j <= N; ++j)
    EXPECT_EQ(t.positions[static_cast<std::size_t>(j)], t.positions[static_cast<std::size_t>(M * (N + 1) + j)]);
  EXPECT_EQ(t.positions[0], t.positions[static_cast<std::size_t>(N)]);
}

TEST(PrimitiveTorus, ColourSweepsFromBlueToRed) {
  const Mesh t = make_torus(2.0f, 0.5f, 8, 4);
  EXPECT_EQ(t.colors.front(), glm::vec4(0, 0, 1, 1));
  EXPECT_EQ(t.colors.back(), glm::vec4(1, 0, 0, 1));
  for (std::size_t ring = 0; ring <= 8; ++ring)
    for (std::size_t j = 0; j <= 4; ++j) {
      const glm::vec4 c = t.colors[ring * 5 + j];
      EXPECT_FLOAT_EQ(c.r, static_cast<float>(ring) / 8);
      EXPECT_FLOAT_EQ(c.r + c.b, 1.0f);
      EXPECT_EQ(c.g, 0.0f);
      EXPECT_EQ(t.uvs[ring * 5 + j], glm::vec2(static_cast<float>(ring) / 8, static_cast<float>(j) / 4));
    }
  // Around the z axis: everything within the slab |z| <= minor radius.
  const Bounds b = bounds(t);
  EXPECT_NEAR(b.max.z, 0.5f, 1e-6f);
  EXPECT_NEAR(b.max.x, 2.5f, 1e-6f);
}

TEST(PrimitiveSphere, MatchesTheBenchmarkConstruction) {
  const int n = 16;
  const Mesh s = make_uv_sphere(n, n);
  EXPECT_EQ(s.vertex_count(), static_cast<std::size_t>((n + 1) * (n + 1)));
  EXPECT_EQ(s.triangle_count(), static_cast<std::size_t>(2 * n * (n - 1)));
  EXPECT_EQ(s.normals, s.positions);
  for (const glm::vec3& p : s.positions) EXPECT_NEAR(glm::length(p), 1.0f, 1e-6f);
  // Vertex i*(n+1)+j, float formulas of BENCHMARK.md 8.1.
  const float pi = 3.14159265358979f;
  const int i = 5, j = 7;
  const float theta = pi * i / n, phi = 2.f * pi * j / n;
  const std::size_t v = static_cast<std::size_t>(i * (n + 1) + j);
  EXPECT_EQ(s.positions[v],
            glm::vec3(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi)));
  EXPECT_EQ(s.uvs[v], glm::vec2(8.f * j / n, 4.f * i / n));
  EXPECT_EQ(s.positions[0], glm::vec3(0, 1, 0));
  // First triangles: row 0 keeps only (a+1, b+1, b).
  EXPECT_EQ(std::vector<std::uint32_t>(s.indices.begin(), s.indices.begin() + 3),
            (std::vector<std::uint32_t>{1, static_cast<std::uint32_t>(n + 2), static_cast<std::uint32_t>(n + 1)}));
  EXPECT_EQ(boundary_edges(s), 0);
  EXPECT_GT(signed_volume(s), 0.9 * 4.0 / 3.0 * std::numbers::pi);
  for (std::size_t t = 0; t < s.triangle_count(); ++t) {
    const glm::vec3 centroid = (corner(s, t, 0) + corner(s, t, 1) + corner(s, t, 2)) / 3.0f;
    EXPECT_GT(glm::dot(face_normal(s, t), centroid), 0) << "triangle " << t;
  }
}

TEST(PrimitiveSphere, BenchmarkSizesAndOtherShapes) {
  EXPECT_EQ(make_uv_sphere(224, 224).triangle_count(), 99904u);  // BENCHMARK.md 8.1: sphere:224
  const Mesh s = make_uv_sphere(3, 8, {1, 1});
  EXPECT_EQ(s.triangle_count(), 2u * 8u * 2u);
  EXPECT_EQ(boundary_edges(s), 0);
  EXPECT_EQ(s.uvs.back(), glm::vec2(1, 1));
  EXPECT_EQ(make_uv_sphere(2, 3).triangle_count(), 6u);  // two pole fans
}

TEST(PrimitivePentagon, FanWithCornerColours) {
  const Mesh p = make_pentagon();
  EXPECT_EQ(p.vertex_count(), 5u);
  EXPECT_EQ(p.triangle_count(), 3u);
  EXPECT_EQ(p.indices, (std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3, 0, 3, 4}));
  EXPECT_EQ(boundary_edges(p), 5);  // open: the 5 sides; the 2 diagonals are shared
  EXPECT_EQ(unique_edges(p).size(), 7u);
  double area = 0;
  for (std::size_t t = 0; t < 3; ++t) {
    const glm::vec3 n = face_normal(p, t);
    EXPECT_GT(n.z, 0);
    EXPECT_NEAR(n.x, 0.0f, 1e-6f);
    area += 0.5 * n.z;
  }
  EXPECT_NEAR(area, 2.5 * std::sin(2 * std::numbers::pi / 5), 1e-5);
  EXPECT_NEAR(p.positions[0].y, 1.0f, 1e-7f);
  std::set<std::tuple<float, float, float>> colours;
  for (const glm::vec4& c : p.colors) colours.insert({c.r, c.g, c.b});
  EXPECT_EQ(colours.size(), 5u);
  for (const glm::vec3& n : p.normals) EXPECT_EQ(n, glm::vec3(0, 0, 1));
}

TEST(PrimitiveArguments, InvalidArgumentsThrow) {
  EXPECT_THROW(make_torus(1, 0.2f, 2, 8), std::invalid_argument);
  EXPECT_THROW(make_torus(1, 0.2f, 8, 2), std::invalid_argument);
  EXPECT_THROW(make_torus(-1, 0.2f, 8, 8), std::invalid_argument);
  EXPECT_THROW(make_torus(1, NAN, 8, 8), std::invalid_argument);
  EXPECT_THROW(make_torus(1, 0.2f, 1 << 20, 1 << 20), std::invalid_argument);
  EXPECT_THROW(make_uv_sphere(1, 8), std::invalid_argument);
  EXPECT_THROW(make_uv_sphere(8, 2), std::invalid_argument);
  EXPECT_THROW(make_uv_sphere(1 << 17, 1 << 17), std::invalid_argument);
}

}  // namespace
}  // namespace facet::primitives_tests
