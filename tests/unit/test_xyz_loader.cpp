// test_xyz_loader.cpp - load_xyz: point clouds as text (.xyz, .pts), their column layouts and their bad input.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "facet/error.hpp"
#include "job/io/loaders.hpp"

namespace facet::xyz_loader_tests {
namespace {

std::string problem(const std::string& text) {
  try {
    (void)load_xyz(text, "cloud.xyz");
  } catch (const InputError& e) {
    EXPECT_EQ(e.source(), "cloud.xyz");
    return e.problem();
  }
  return "";
}

TEST(XyzLoader, PositionsAloneEachAPoint) {
  const Mesh m = load_xyz("# x y z\n\n1 2 3\n  -4.5\t5e1 6\r\n// a comment\n7,8,9\n", "c.xyz");
  ASSERT_EQ(m.positions.size(), 3u);
  EXPECT_EQ(m.positions[0], glm::vec3(1, 2, 3));
  EXPECT_EQ(m.positions[1], glm::vec3(-4.5f, 50, 6));
  EXPECT_EQ(m.positions[2], glm::vec3(7, 8, 9));
  EXPECT_EQ(m.points, (std::vector<std::uint32_t>{0, 1, 2}));
  EXPECT_TRUE(m.colors.empty());
  EXPECT_TRUE(m.normals.empty());
  EXPECT_EQ(m.triangle_count(), 0u);
}

TEST(XyzLoader, ThreeMoreColumnsAreNormalsWhenAllAreUnitVectorsElseColours) {
  const Mesh normals = load_xyz("0 0 0 0 0 1\n1 0 0 0.6 0.8 0\n", "n.xyz");
  ASSERT_EQ(normals.normals.size(), 2u);
  EXPECT_EQ(normals.normals[1], glm::vec3(0.6f, 0.8f, 0));
  EXPECT_TRUE(normals.colors.empty());
  // Bytes (one above 1): scaled from 0..255.
  const Mesh bytes = load_xyz("0 0 0 255 0 51\n1 0 0 0 0 1\n", "b.xyz");
  ASSERT_EQ(bytes.colors.size(), 2u);
  EXPECT_EQ(bytes.colors[0], glm::vec4(1, 0, 0.2f, 1));
  EXPECT_TRUE(bytes.normals.empty());
  // All within 0..1 and not unit vectors: colours as they are.
  const Mesh unit = load_xyz("0 0 0 0.5 0.25 0\n", "u.xyz");
  ASSERT_EQ(unit.colors.size(), 1u);
  EXPECT_EQ(unit.colors[0], glm::vec4(0.5f, 0.25f, 0, 1));
}

TEST(XyzLoader, PtsRowsAreIntensityThenColourAfterAPointCount) {
  const Mesh m = load_xyz("2\n0 0 0 -1200 255 0 0\n1 1 1 300 0 255 0\n", "scan.pts");
  ASSERT_EQ(m.points.size(), 2u);
  ASSERT_EQ(m.colors.size(), 2u);
  EXPECT_EQ(m.colors[1], glm::vec4(0, 1, 0, 1));
  EXPECT_EQ(m.positions[1], glm::vec3(1, 1, 1));
  EXPECT_EQ(m.intensities, (std::vector<float>{-1200, 300}));
}

// x y z and one more column: a scan's intensity, as LiDAR tools export text.
TEST(XyzLoader, OneMoreColumnIsIntensity) {
  const Mesh m = load_xyz("0 0 0 17\n1 0 0 3.5\n", "scan.xyz");
  EXPECT_EQ(m.intensities, (std::vector<float>{17, 3.5f}));
  EXPECT_TRUE(m.colors.empty());
  EXPECT_TRUE(m.normals.empty());
}

TEST(XyzLoader, NineColumnsHoldColoursAndNormalsInEitherOrder) {
  const Mesh normals_first = load_xyz("0;0;0;0;0;1;10;20;30\n1;1;1;1;0;0;40;50;60\n", "a.xyz");
  ASSERT_EQ(normals_first.normals.size(), 2u);
  EXPECT_EQ(normals_first.normals[1], glm::vec3(1, 0, 0));
  EXPECT_EQ(normals_first.colors[1], glm::vec4(40 / 255.0f, 50 / 255.0f, 60 / 255.0f, 1));
  const Mesh colours_first = load_xyz("0 0 0 10 20 30 0 0 1\n", "b.xyz");
  EXPECT_EQ(colours_first.normals[0], glm::vec3(0, 0, 1));
  EXPECT_EQ(colours_first.colors[0], glm::vec4(10 / 255.0f, 20 / 255.0f, 30 / 255.0f, 1));
}

TEST(XyzLoader, BadRowsAreOneLineErrorsNamingTheLine) {
  EXPECT_EQ(problem(""), "nothing to draw (no points)");
  EXPECT_EQ(problem("# only a comment\n\n"), "nothing to draw (no points)");
  EXPECT_EQ(problem("1 2 3\n4 5\n"), "line 2: 2 numbers where the first point has 3");
  EXPECT_EQ(problem("1 2\n"), "line 1: 2 numbers, not a point's x y z");
  EXPECT_EQ(problem("1 2 3\n4 five 6\n"), "line 2: 'five' is not a number");
  EXPECT_EQ(problem("1 2 3\nnan 0 0\n"), "line 2: the position is not finite");
  EXPECT_EQ(problem("1 2 3\n0 1e39 0\n"), "line 2: the position is not finite");
  EXPECT_EQ(problem("5\n6\n"), "line 2: 1 numbers, not a point's x y z");
}

}  // namespace
}  // namespace facet::xyz_loader_tests
