// test_mesh.cpp - unit tests for mesh.hpp: strips, fans, polygons, edges, smooth and crease normals, bounds, buffers.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <map>
#include <numbers>
#include <set>
#include <string>
#include <vector>

#include "facet/error.hpp"
#include "facet/mesh.hpp"
#include "facet/primitives.hpp"
#include "scene/mesh/crease_normals.hpp"

namespace facet::mesh_tests {
namespace {

using Indices = std::vector<std::uint32_t>;

// Runs fn, which must throw InputError; returns its what() (empty if nothing was thrown).
template <typename Fn>
std::string input_error(Fn&& fn) {
  try {
    fn();
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "expected an InputError";
  return {};
}

bool starts_with(const std::string& s, const std::string& prefix) { return s.rfind(prefix, 0) == 0; }

glm::vec3 face_normal(const Mesh& m, std::size_t t) {
  const glm::vec3 a = m.positions[m.indices[3 * t]], b = m.positions[m.indices[3 * t + 1]],
                  c = m.positions[m.indices[3 * t + 2]];
  return glm::cross(b - a, c - a);
}

// Signed volume of a closed mesh: positive when every triangle winds counter-clockwise seen from outside.
double signed_volume(const Mesh& m) {
  double v = 0;
  for (std::size_t t = 0; t < m.triangle_count(); ++t) {
    const glm::dvec3 a = m.positions[m.indices[3 * t]], b = m.positions[m.indices[3 * t + 1]],
                     c = m.positions[m.indices[3 * t + 2]];
    v += glm::dot(a, glm::cross(b, c)) / 6.0;
  }
  return v;
}

// The cube of the CIS367 lecture notes "Building models / Viewing": 8 vertices and 6 quads listed so the normals
// point outwards.
PolygonMesh lecture_cube() {
  PolygonMesh p;
  p.positions = {{-0.5f, -0.5f, 0.5f},  {-0.5f, 0.5f, 0.5f},  {0.5f, 0.5f, 0.5f},  {0.5f, -0.5f, 0.5f},
                 {-0.5f, -0.5f, -0.5f}, {-0.5f, 0.5f, -0.5f}, {0.5f, 0.5f, -0.5f}, {0.5f, -0.5f, -0.5f}};
  p.polygons = {{1, 0, 3, 2}, {2, 3, 7, 6}, {3, 0, 4, 7}, {6, 5, 1, 2}, {4, 5, 6, 7}, {5, 4, 0, 1}};
  return p;
}

// A cube of side 1 around the origin as 8 shared corners and no normals: faces +z, -z, +x, -x, +y, -y, two
// triangles each, as a model file without normals gives it.
Mesh shared_cube() {
  Mesh m;
  for (int i = 0; i < 8; ++i)
    m.positions.emplace_back((i & 1) ? 0.5f : -0.5f, (i & 2) ? 0.5f : -0.5f, (i & 4) ? 0.5f : -0.5f);
  const std::uint32_t quads[6][4] = {{4, 5, 7, 6}, {1, 0, 2, 3}, {5, 1, 3, 7},
                                     {0, 4, 6, 2}, {6, 7, 3, 2}, {0, 1, 5, 4}};
  for (const auto& q : quads) m.indices.insert(m.indices.end(), {q[0], q[1], q[2], q[0], q[2], q[3]});
  return m;
}

bool all_finite(const std::vector<glm::vec3>& normals) {
  for (const glm::vec3& n : normals)
    if (!std::isfinite(n.x) || !std::isfinite(n.y) || !std::isfinite(n.z)) return false;
  return true;
}

TEST(MeshStrip, AlternateTrianglesAreFlippedToCounterClockwise) {
  // A ladder going up in y: even strip positions on the left, odd ones on the right.
  const std::vector<glm::vec3> pos = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {0, 2, 0}, {1, 2, 0}};
  const Indices strip = {0, 1, 2, 3, 4, 5};
  const Indices tris = triangles_from_strip(strip);
  EXPECT_EQ(tris, (Indices{0, 1, 2, 2, 1, 3, 2, 3, 4, 4, 3, 5}));
  Mesh m;
  m.positions = pos;
  m.indices = tris;
  for (std::size_t t = 0; t < m.triangle_count(); ++t) EXPECT_GT(face_normal(m, t).z, 0) << "triangle " << t;
}

TEST(MeshStrip, DegenerateJoinsAreDroppedAndParityKept) {
  // Two strips joined by repeating 3 and 4; the second strip starts on an even triangle again.
  const Indices strip = {0, 1, 2, 3, 3, 4, 4, 5, 6, 7};
  EXPECT_EQ(triangles_from_strip(strip), (Indices{0, 1, 2, 2, 1, 3, 4, 5, 6, 6, 5, 7}));
  EXPECT_TRUE(triangles_from_strip(Indices{0, 1}).empty());
  EXPECT_TRUE(triangles_from_strip(Indices{}).empty());
  EXPECT_TRUE(triangles_from_strip(Indices{5, 5, 5, 5}).empty());
}

TEST(MeshFan, FanAroundFirstIndexDropsRepeats) {
  EXPECT_EQ(triangles_from_fan(Indices{0, 1, 2, 3, 4}), (Indices{0, 1, 2, 0, 2, 3, 0, 3, 4}));
  EXPECT_EQ(triangles_from_fan(Indices{0, 1, 1, 2}), (Indices{0, 1, 2}));
  EXPECT_TRUE(triangles_from_fan(Indices{7, 8}).empty());
}

TEST(MeshPolygon, LectureCubeEdgesAndTriangulation) {
  const PolygonMesh cube = lecture_cube();
  EXPECT_EQ(unique_edges(cube).size(), 12u);  // the cube's real edges
  const Mesh tri = triangulate(cube);
  EXPECT_EQ(tri.vertex_count(), 8u);
  EXPECT_EQ(tri.triangle_count(), 12u);
  // quad(1, 0, 3, 2) fans into (1 0 3) and (1 3 2).
  EXPECT_EQ(Indices(tri.indices.begin(), tri.indices.begin() + 6), (Indices{1, 0, 3, 1, 3, 2}));
  const auto edges = unique_edges(tri);
  EXPECT_EQ(edges.size(), 18u);  // 12 cube edges + one diagonal per face
  std::map<std::array<std::uint32_t, 2>, int> uses;
  for (std::size_t i = 0; i < tri.indices.size(); i += 3)
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = tri.indices[i + k], b = tri.indices[i + (k + 1) % 3];
      ++uses[{std::min(a, b), std::max(a, b)}];
    }
  for (const auto& e : edges) EXPECT_EQ(uses[e], 2) << e[0] << "-" << e[1];
  EXPECT_NEAR(signed_volume(tri), 1.0, 1e-6);  // unit cube, outward winding
}

TEST(MeshPolygon, ConcavePolygonIsEarClipped) {
  // An L shape (area 3, reflex corner 3 at (1, 1)). Listed from corner 1 at (2, 0), whose fan would cross the
  // notch: (1 3 4) would be clockwise.
  PolygonMesh l;
  l.positions = {{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}, {1, 2, 0}, {0, 2, 0}};
  l.polygons = {{1, 2, 3, 4, 5, 0}};
  const Mesh m = triangulate(l);
  ASSERT_EQ(m.triangle_count(), 4u);
  double area = 0;
  for (std::size_t t = 0; t < 4; ++t) {
    const glm::vec3 n = face_normal(m, t);
    EXPECT_GT(n.z, 0) << "triangle " << t;
    area += 0.5 * n.z;
  }
  EXPECT_NEAR(area, 3.0, 1e-6);
}

TEST(MeshPolygon, BadPolygonsThrow) {
  PolygonMesh p = lecture_cube();
  p.polygons.push_back({0, 1});
  EXPECT_TRUE(starts_with(input_error([&] { triangulate(p); }), "polygon mesh: polygon 6 has 2 corners"));
  p.polygons.back() = {0, 1, 8};
  EXPECT_NE(input_error([&] { triangulate(p); }).find("vertex 8"), std::string::npos);
}

TEST(MeshEdges, CubeVariants) {
  EXPECT_EQ(unique_edges(make_cube()).size(), 30u);  // 6 separate faces x (4 sides + 1 diagonal)
  Mesh soup;
  soup.indices = {0, 1, 2, 3, 4, 5};
  EXPECT_EQ(unique_edges(soup).size(), 6u);
  Mesh shared;
  shared.indices = {2, 1, 0, 0, 2, 3, 1, 1, 2};  // the last triangle is degenerate
  const auto edges = unique_edges(shared);
  EXPECT_EQ(edges, (std::vector<std::array<std::uint32_t, 2>>{{0, 1}, {0, 2}, {0, 3}, {1, 2}, {2, 3}}));
}

TEST(MeshNormals, SphereNormalsPointAlongPositions) {
  Mesh s = make_uv_sphere(24, 32);
  s.normals.clear();
  compute_smooth_normals(s);
  ASSERT_EQ(s.normals.size(), s.positions.size());
  // Skipped: the seam columns and the -y pole row, whose copies are not equal in float (sin(float(2 pi)) and
  // sin(float(pi)) are not 0), so each copy only sees its own triangles - as in the reference renderer.
  for (int i = 0; i < 24; ++i)
    for (int j = 1; j < 32; ++j) {
      const std::size_t v = static_cast<std::size_t>(i * 33 + j);
      EXPECT_NEAR(glm::length(s.normals[v]), 1.0f, 1e-5f);
      EXPECT_GT(glm::dot(s.normals[v], s.positions[v]), 0.999f) << "vertex " << v;
    }
  EXPECT_NEAR(s.normals[0].y, 1.0f, 1e-6f);  // all pole copies share one group (+0 and -0 compare equal)
}

TEST(MeshNormals, TorusNormalsMatchAnalyticOnesAcrossSeams) {
  Mesh t = make_torus(1.0f, 0.3f, 48, 24);
  const std::vector<glm::vec3> analytic = t.normals;
  compute_smooth_normals(t);
  for (std::size_t v = 0; v < t.vertex_count(); ++v) EXPECT_GT(glm::dot(t.normals[v], analytic[v]), 0.998f) << v;
  // Seam copies share bits, so they get identical normals.
  EXPECT_EQ(t.normals[0], t.normals[48 * 25]);
  EXPECT_EQ(t.normals[0], t.normals[24]);
}

TEST(MeshNormals, AreaWeightingSplitVerticesAndZeroSum) {
  // Two triangles meeting at the origin: one large in the z = 0 plane, one small in the x = 0 plane; the origin
  // is split into two vertices (0 and 3) that must share the area-weighted normal.
  Mesh m;
  m.positions = {{0, 0, 0}, {4, 0, 0}, {0, 4, 0}, {-0.0f, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  m.indices = {0, 1, 2, 3, 4, 5};
  compute_smooth_normals(m);
  const glm::vec3 expected = glm::normalize(glm::vec3(1, 0, 16));  // (1, 0, 0) from the small one, 16 z from the big
  EXPECT_NEAR(glm::distance(m.normals[0], expected), 0.0f, 1e-6f);
  EXPECT_EQ(m.normals[0], m.normals[3]);
  EXPECT_EQ(m.normals[1], glm::vec3(0, 0, 1));
  EXPECT_EQ(m.normals[4], glm::vec3(1, 0, 0));
  // A degenerate triangle contributes nothing, so its vertices fall back to (0, 0, 1).
  Mesh d;
  d.positions = {{1, 1, 1}, {1, 1, 1}, {2, 2, 2}, {5, 5, 5}};
  d.indices = {0, 1, 2};
  compute_smooth_normals(d);
  for (const glm::vec3& n : d.normals) EXPECT_EQ(n, glm::vec3(0, 0, 1));
}

TEST(MeshCreaseNormals, SharedCubeCornersSplitIntoFlatFaces) {
  Mesh m = shared_cube();
  for (int i = 0; i < 8; ++i) {
    m.colors.emplace_back(i / 8.0f, 0.5f, 1.0f, 1.0f);  // per-vertex attributes must follow the split copies
    m.uvs.emplace_back(i / 8.0f, 1.0f - i / 8.0f);
  }
  const Mesh before = m;
  compute_crease_normals(m, glm::radians(60.0f));
  validate(m, "creased cube");
  ASSERT_EQ(m.vertex_count(), 24u);  // each corner once per face meeting there
  ASSERT_EQ(m.triangle_count(), 12u);
  const glm::vec3 axes[6] = {{0, 0, 1}, {0, 0, -1}, {1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}};
  for (std::size_t t = 0; t < 12; ++t)
    for (std::size_t k = 0; k < 3; ++k) {
      const std::uint32_t was = before.indices[3 * t + k], now = m.indices[3 * t + k];
      EXPECT_EQ(m.positions[now], before.positions[was]);
      EXPECT_EQ(m.colors[now], before.colors[was]);
      EXPECT_EQ(m.uvs[now], before.uvs[was]);
      EXPECT_EQ(m.normals[now], axes[t / 2]) << "triangle " << t << " corner " << k;  // exactly, not nearly
    }
  // Still indexed: each face's two triangles share their diagonal (4 vertices a face), and no face shares a vertex
  // with another; the original 8 vertices keep their indices, the copies come after them.
  std::set<std::uint32_t> used;
  for (std::size_t face = 0; face < 6; ++face) {
    const std::set<std::uint32_t> corners(m.indices.begin() + static_cast<std::ptrdiff_t>(6 * face),
                                          m.indices.begin() + static_cast<std::ptrdiff_t>(6 * face + 6));
    EXPECT_EQ(corners.size(), 4u) << "face " << face;
    used.insert(corners.begin(), corners.end());
  }
  EXPECT_EQ(used.size(), 24u);
  for (std::size_t v = 0; v < 8; ++v) EXPECT_EQ(m.positions[v], before.positions[v]);
}

TEST(MeshCreaseNormals, HingeSplitsOnlyBeyondTheCreaseAngle) {
  // Two unit squares sharing the edge from (0, 0, 0) to (0, 1, 0): one flat (+z), one folded down by 45 degrees.
  const float c = std::sqrt(0.5f);
  Mesh m;
  m.positions = {{0, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {-1, 1, 0}, {c, 0, -c}, {c, 1, -c}};
  m.indices = {2, 0, 1, 2, 1, 3, 0, 4, 5, 0, 5, 1};
  const glm::vec3 flat(0, 0, 1), folded(c, 0, c);

  Mesh tight = m;
  compute_crease_normals(tight, glm::radians(30.0f));
  EXPECT_EQ(tight.vertex_count(), 8u);  // both hinge vertices split
  for (std::size_t corner = 0; corner < 12; ++corner)
    EXPECT_LT(glm::distance(tight.normals[tight.indices[corner]], corner < 6 ? flat : folded), 1e-6f) << corner;

  Mesh loose = m;
  compute_crease_normals(loose, glm::radians(60.0f));
  EXPECT_EQ(loose.vertex_count(), 6u);
  EXPECT_EQ(loose.indices, m.indices);
  for (const std::uint32_t hinge : {0u, 1u}) {  // between the two faces
    const glm::vec3 n = loose.normals[hinge];
    EXPECT_NEAR(glm::length(n), 1.0f, 1e-6f);
    EXPECT_GT(glm::dot(n, flat), std::cos(glm::radians(45.0f)) + 0.01f);
    EXPECT_GT(glm::dot(n, folded), std::cos(glm::radians(45.0f)) + 0.01f);
  }
  EXPECT_EQ(loose.normals[2], flat);
  EXPECT_LT(glm::distance(loose.normals[4], folded), 1e-6f);

  // A two-sided sheet (each triangle also listed with the opposite winding) gets one vertex per side, where smooth
  // normals would cancel to nothing.
  Mesh sheet;
  sheet.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  sheet.indices = {0, 1, 2, 0, 2, 3, 0, 2, 1, 0, 3, 2};
  compute_crease_normals(sheet, glm::radians(60.0f));
  EXPECT_EQ(sheet.vertex_count(), 8u);
  for (std::size_t corner = 0; corner < 12; ++corner)
    EXPECT_EQ(sheet.normals[sheet.indices[corner]], glm::vec3(0, 0, corner < 6 ? 1 : -1)) << corner;

  // A tilted plane at crease angle 0: its triangles' unit normals differ in the last bits, which must not split it.
  Mesh plane;
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) plane.positions.emplace_back(0.37f * x, 0.29f * y, 0.3f * x + 0.7f * y);
  for (std::uint32_t y = 0; y < 3; ++y)
    for (std::uint32_t x = 0; x < 3; ++x) {
      const std::uint32_t v = 4 * y + x;
      plane.indices.insert(plane.indices.end(), {v, v + 1, v + 5, v, v + 5, v + 4});
    }
  compute_crease_normals(plane, 0.0f);
  EXPECT_EQ(plane.vertex_count(), 16u);
}

TEST(MeshCreaseNormals, FineSphereStaysSmoothAndShared) {
  for (const float degrees : {30.0f, 60.0f}) {
    Mesh s = make_uv_sphere(24, 32);
    s.normals.clear();
    const std::vector<std::uint32_t> indices = s.indices;
    Mesh smooth = s;
    compute_smooth_normals(smooth);
    compute_crease_normals(s, glm::radians(degrees));
    ASSERT_EQ(s.vertex_count(), smooth.vertex_count()) << degrees;
    EXPECT_EQ(s.indices, indices);
    EXPECT_EQ(s.normals, smooth.normals);  // no face is cut off anywhere, so the sums are the smooth ones
    // As for compute_smooth_normals, the seam columns and the -y pole row (copies not equal in float) are skipped.
    for (int i = 0; i < 24; ++i)
      for (int j = 1; j < 32; ++j) {
        const std::size_t v = static_cast<std::size_t>(i * 33 + j);
        EXPECT_NEAR(glm::length(s.normals[v]), 1.0f, 1e-5f);
        EXPECT_GT(glm::dot(s.normals[v], s.positions[v]), 0.999f) << "vertex " << v;
      }
  }
}

TEST(MeshCreaseNormals, DegenerateTrianglesMakeNoNaN) {
  Mesh m;
  m.positions = {{0, 0, 0},     {0, 1, 0},     {0, 0, 1},     {0, 2, 0},  // 0-2 a real triangle (+x); 3 collinear
                 {1, 1, 1},     {2, 2, 2},     {3, 3, 3},                 // 4-6 collinear
                 {1e30f, 0, 0}, {0, 1e30f, 0}, {0, 0, 1e30f},             // 7-9 a normal that overflows to inf
                 {-0.0f, 0, 0}, {7, 7, 7}};                               // 10 at vertex 0's position; 11 unused
  m.indices = {0, 1, 2, 0, 1, 3, 2, 2, 0, 4, 5, 6, 7, 8, 9, 10, 10, 1};
  const std::vector<std::uint32_t> indices = m.indices;
  compute_crease_normals(m, glm::radians(60.0f));
  EXPECT_EQ(m.vertex_count(), 12u);  // degenerate triangles split nothing
  EXPECT_EQ(m.indices, indices);
  ASSERT_TRUE(all_finite(m.normals));
  for (const std::size_t v : {0, 1, 2}) EXPECT_EQ(m.normals[v], glm::vec3(1, 0, 0)) << v;
  // Only in degenerate triangles, so no face of their own: the smooth normal at their position, else (0, 0, 1).
  EXPECT_EQ(m.normals[10], glm::vec3(1, 0, 0));
  for (const std::size_t v : {3, 4, 5, 6, 7, 8, 9, 11}) EXPECT_EQ(m.normals[v], glm::vec3(0, 0, 1)) << v;

  Mesh only;  // nothing but degenerate triangles, and an index out of range, which is left as it is
  only.positions = {{1, 1, 1}, {1, 1, 1}, {2, 2, 2}};
  only.indices = {0, 1, 2, 0, 1, 9};
  compute_crease_normals(only, glm::radians(60.0f));
  EXPECT_EQ(only.indices, (std::vector<std::uint32_t>{0, 1, 2, 0, 1, 9}));
  EXPECT_EQ(only.normals, std::vector<glm::vec3>(3, glm::vec3(0, 0, 1)));
}

TEST(MeshCreaseNormals, StraightAngleReproducesSmoothNormals) {
  Mesh torus = make_torus(1.0f, 0.3f, 48, 24);
  torus.normals.clear();
  Mesh sphere = make_uv_sphere(12, 16);
  sphere.normals.clear();
  Mesh area;  // from AreaWeightingSplitVerticesAndZeroSum: faces at 90 degrees, and a split vertex
  area.positions = {{0, 0, 0}, {4, 0, 0}, {0, 4, 0}, {-0.0f, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  area.indices = {0, 1, 2, 3, 4, 5};
  for (const Mesh& mesh : {torus, sphere, area, shared_cube()}) {
    Mesh smooth = mesh, creased = mesh;
    compute_smooth_normals(smooth);
    compute_crease_normals(creased, std::numbers::pi_v<float>);
    EXPECT_EQ(creased.positions, smooth.positions);
    EXPECT_EQ(creased.indices, smooth.indices);
    EXPECT_EQ(creased.normals, smooth.normals);  // the same sums in the same order: equal bits
  }
}

// Large meshes are split over threads (counting sorts, groups, vertices in parts); every split gives one thread's
// result. The mesh: a fine torus (smooth), a folded sheet whose folds are creases (vertices split and copied with
// their uvs and colours), and degenerate and out-of-range triangles scattered through it, parts' borders included.
TEST(MeshCreaseNormals, AnyNumberOfThreadsGivesOneThreadsResult) {
  Mesh mesh = make_torus(1.0f, 0.3f, 256, 128);  // 65,536 triangles
  const int side = 160;                           // the sheet: 2 x 159 x 159 triangles, folded every third column
  const auto base = static_cast<std::uint32_t>(mesh.positions.size());
  for (int j = 0; j < side; ++j)
    for (int i = 0; i < side; ++i)
      mesh.positions.push_back({3.0f + 0.01f * i, 0.01f * j, (i % 3 == 0) ? 0.02f : 0.0f});
  for (int j = 0; j + 1 < side; ++j)
    for (int i = 0; i + 1 < side; ++i) {
      const std::uint32_t a = base + static_cast<std::uint32_t>(j * side + i), b = a + 1, c = a + side, d = c + 1;
      mesh.indices.insert(mesh.indices.end(), {a, b, d, a, d, c});
    }
  const auto n = static_cast<std::uint32_t>(mesh.positions.size());
  for (std::size_t t = 0; t < mesh.indices.size() / 3; t += 9973) mesh.indices[3 * t + 1] = mesh.indices[3 * t];
  mesh.indices[3 * 50000 + 2] = n + 5;  // out of range
  mesh.normals.clear();
  mesh.uvs.resize(n);
  mesh.colors.resize(n);
  for (std::uint32_t v = 0; v < n; ++v) {
    mesh.uvs[v] = glm::vec2(static_cast<float>(v % 97), static_cast<float>(v % 89));
    mesh.colors[v] = glm::vec4(static_cast<float>(v % 7) / 7.0f, 0.5f, 1.0f, 1.0f);
  }
  Mesh one = mesh;
  detail::compute_crease_normals_in_parts(one, glm::radians(30.0f), 1);
  ASSERT_GT(one.positions.size(), mesh.positions.size() + 10000);  // the folds split vertices
  for (const int parts : {2, 3, 4, 7}) {
    Mesh split = mesh;
    detail::compute_crease_normals_in_parts(split, glm::radians(30.0f), parts);
    EXPECT_EQ(split.indices, one.indices) << parts << " parts";
    EXPECT_EQ(split.positions, one.positions) << parts << " parts";
    EXPECT_EQ(split.normals, one.normals) << parts << " parts";
    EXPECT_EQ(split.uvs, one.uvs) << parts << " parts";
    EXPECT_EQ(split.colors, one.colors) << parts << " parts";
  }
}

TEST(MeshBounds, CubeSphereAndEmpty) {
  const Bounds b = bounds(make_cube());
  EXPECT_EQ(b.min, glm::vec3(-1));
  EXPECT_EQ(b.max, glm::vec3(1));
  EXPECT_EQ(b.center(), glm::vec3(0));
  EXPECT_NEAR(b.radius(), std::sqrt(3.0f), 1e-6f);
  EXPECT_FALSE(b.empty());

  Mesh m;
  EXPECT_TRUE(bounds(m).empty());
  EXPECT_EQ(bounds(m).radius(), 0.0f);
  m.positions = {{1, 2, 3}, {5, -2, 3}, {100, 100, 100}};  // the last is not referenced but still counts
  m.indices = {0, 1, 0};
  const Bounds c = bounds(m);
  EXPECT_EQ(c.min, glm::vec3(1, -2, 3));
  EXPECT_EQ(c.max, glm::vec3(100, 100, 100));
  EXPECT_EQ(c.center(), glm::vec3(50.5f, 49.0f, 51.5f));
}

std::vector<std::byte> to_bytes(const std::vector<float>& f, std::size_t lead = 0) {
  std::vector<std::byte> b(lead + f.size() * sizeof(float));
  std::memcpy(b.data() + lead, f.data(), f.size() * sizeof(float));
  return b;
}

TEST(MeshInterleaved, ColoredCubeRoundTrip) {
  const std::vector<float> data = colored_cube_vertex_data();
  ASSERT_EQ(data.size(), 36u * 6u);
  // One leading byte makes every float unaligned.
  const std::vector<std::byte> bytes = to_bytes(data, 1);
  VertexLayout layout;
  layout.stride = 24;
  layout.position_offset = 0;
  layout.color_offset = 12;
  const Mesh m = mesh_from_interleaved(std::span(bytes).subspan(1), layout);
  EXPECT_EQ(m.vertex_count(), 36u);
  EXPECT_EQ(m.triangle_count(), 12u);
  EXPECT_TRUE(m.normals.empty());
  EXPECT_TRUE(m.uvs.empty());
  ASSERT_EQ(m.colors.size(), 36u);
  const Mesh cube = make_cube();
  for (std::size_t t = 0; t < 12; ++t) {
    for (int c = 0; c < 3; ++c) {
      const std::size_t k = 3 * t + static_cast<std::size_t>(c);
      EXPECT_EQ(m.positions[m.indices[k]], cube.positions[cube.indices[k]]) << "corner " << k;
      EXPECT_EQ(m.colors[m.indices[k]], cube.face_colors[t]) << "corner " << k;
    }
  }
  EXPECT_EQ(m.colors[0], glm::vec4(1, 0, 0, 1));   // front red
  EXPECT_EQ(m.colors[35], glm::vec4(0, 1, 1, 1));  // bottom cyan
  EXPECT_NEAR(signed_volume(m), 8.0, 1e-9);
}

TEST(MeshInterleaved, IndexedWithAllAttributes) {
  // Per vertex: uv(2) pad(1) position(3) normal(3) rgba(4) = 13 floats, an unusual order on purpose.
  std::vector<float> f;
  for (int v = 0; v < 3; ++v) {
    const float x = static_cast<float>(v);
    f.insert(f.end(), {x / 2, 1 - x / 2, -7, x, x * x, 0, 0, 0, 1, 0.25f * x, 0.5f, 0.75f, 1});
  }
  VertexLayout layout;
  layout.stride = 52;
  layout.uv_offset = 0;
  layout.position_offset = 12;
  layout.normal_offset = 24;
  layout.color_offset = 36;
  layout.color_components = 4;
  const std::vector<std::byte> bytes = to_bytes(f);
  const Indices idx = {0, 1, 2, 2, 1, 0};
  const Mesh m = mesh_from_interleaved(bytes, layout, idx);
  EXPECT_EQ(m.vertex_count(), 3u);
  EXPECT_EQ(m.indices, idx);
  EXPECT_EQ(m.positions[2], glm::vec3(2, 4, 0));
  EXPECT_EQ(m.normals[1], glm::vec3(0, 0, 1));
  EXPECT_EQ(m.uvs[2], glm::vec2(1, 0));
  EXPECT_EQ(m.colors[2], glm::vec4(0.5f, 0.5f, 0.75f, 1));
}

TEST(MeshInterleaved, BadBuffersThrow) {
  const std::vector<std::byte> cube = to_bytes(colored_cube_vertex_data());
  VertexLayout ok;
  ok.stride = 24;
  ok.color_offset = 12;
  auto err = [&](std::span<const std::byte> data, VertexLayout layout, Indices idx = {}) {
    const std::string what = input_error([&] { mesh_from_interleaved(data, layout, idx); });
    EXPECT_TRUE(starts_with(what, "interleaved buffer: ")) << what;
    return what;
  };
  VertexLayout l = ok;
  l.stride = 0;
  EXPECT_NE(err(cube, l).find("stride"), std::string::npos);
  l = ok;
  l.color_offset = 16;  // 16 + 12 > 24
  EXPECT_NE(err(cube, l).find("color at offset 16"), std::string::npos);
  l = ok;
  l.position_offset = static_cast<std::size_t>(-4);  // would wrap around if added naively
  err(cube, l);
  l = ok;
  l.color_components = 2;
  err(cube, l);
  err(std::span(cube).first(cube.size() - 1), ok);                        // not whole vertices
  err(std::span(cube).first(24 * 4), ok);                                 // 4 vertices, not a multiple of 3
  err(std::span<const std::byte>(), ok);                                  // empty
  EXPECT_NE(err(cube, ok, {0, 1, 36}).find("is 36"), std::string::npos);  // index out of range
  err(cube, ok, {0, 1});                                                  // not a multiple of 3
  std::vector<float> nan_data = colored_cube_vertex_data();
  nan_data[6 * 5 + 1] = std::nanf("");
  EXPECT_NE(err(to_bytes(nan_data), ok).find("non-finite vertex position (vertex 5)"), std::string::npos);
}

TEST(MeshValidate, ReportsEachProblem) {
  const Mesh good = make_cube();
  EXPECT_NO_THROW(validate(good, "x"));
  auto err = [](const Mesh& m) { return input_error([&] { validate(m, "model.obj"); }); };

  Mesh m = good;
  m.normals.pop_back();
  EXPECT_EQ(err(m), "model.obj: normals has 23 entries but there are 24 positions");
  m = good;
  m.uvs.push_back({});
  EXPECT_TRUE(starts_with(err(m), "model.obj: uvs has 25 entries"));
  m = good;
  m.indices.push_back(0);
  EXPECT_EQ(err(m), "model.obj: index count 37 is not a multiple of 3");
  m = good;
  m.indices[7] = 99;
  EXPECT_EQ(err(m), "model.obj: index 7 (triangle 2) is 99 but there are only 24 vertices");
  m = good;
  m.face_colors.pop_back();
  EXPECT_TRUE(starts_with(err(m), "model.obj: face_colors has 11 entries but there are 12 triangles"));
  m = good;
  m.face_materials.assign(12, -1);
  EXPECT_NO_THROW(validate(m, "x"));
  m.face_materials[3] = 0;  // no materials
  EXPECT_TRUE(starts_with(err(m), "model.obj: triangle 3 uses material 0"));
  m = good;
  m.positions[5].y = INFINITY;
  EXPECT_EQ(err(m), "model.obj: non-finite vertex position (vertex 5)");
}

}  // namespace
}  // namespace facet::mesh_tests
