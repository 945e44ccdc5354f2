// test_clip.cpp - homogeneous clipping: vertex-inside cases per plane, near-plane crossings, triangles behind the eye.
#include <gtest/gtest.h>

#include <cmath>

#include "core/clip/clip.hpp"

namespace facet::detail::clip_tests {
namespace {

// A triangle straddling frustum plane p (0..5, w +- x, y or z >= 0) with `inside` of its vertices inside; the vertices
// are placed at distance +1 (inside) or -1 (outside) along that plane's axis.
glm::vec4 place(int plane, bool in, glm::vec2 spread) {
  glm::vec4 v(spread.x * 0.2f, spread.y * 0.2f, 0.0f, 2.0f);
  const float d = in ? 1.0f : -1.0f;
  const int axis = plane / 2;
  const float sign = (plane % 2 == 0) ? -1.0f : 1.0f;  // plane 0: x >= -w, plane 1: x <= w
  v[axis] = sign * (v.w - d);
  return v;
}

class ClipPlaneTest : public ::testing::TestWithParam<std::tuple<int, int>> {};

TEST_P(ClipPlaneTest, VerticesInsideDecideThePolygon) {
  const auto [plane, inside] = GetParam();
  const glm::vec2 spread[3] = {{0, 0}, {1, 0}, {0, 1}};
  const glm::vec4 tri[3] = {place(plane, 0 < inside, spread[0]), place(plane, 1 < inside, spread[1]),
                            place(plane, 2 < inside, spread[2])};
  ClipVertex out[kMaxClipVertices];
  const int n = clip_triangle(tri, out);
  const int expected[4] = {0, 3, 4, 3};  // one vertex in: a smaller triangle; two in: a quad; all in: unchanged
  ASSERT_EQ(n, expected[inside]) << "plane " << plane << ", " << inside << " inside";
  for (int k = 0; k < n; ++k) {
    EXPECT_GE(plane_distance(out[k].position, plane), -1e-5f);
    EXPECT_NEAR(out[k].weights.x + out[k].weights.y + out[k].weights.z, 1.0f, 1e-5f);
    // Each output point is the blend of the source corners its weights say.
    const glm::vec4 blended = out[k].weights.x * tri[0] + out[k].weights.y * tri[1] + out[k].weights.z * tri[2];
    for (int c = 0; c < 4; ++c) EXPECT_NEAR(blended[c], out[k].position[c], 1e-4f);
  }
}

INSTANTIATE_TEST_SUITE_P(AllPlanes, ClipPlaneTest, ::testing::Combine(::testing::Range(0, 6), ::testing::Range(0, 4)));

TEST(Clip, TriangleBehindTheEyeIsRejected) {
  const glm::vec4 tri[3] = {{0, 0, 1, -1}, {1, 0, 1, -1}, {0, 1, 1, -2}};
  ClipVertex out[kMaxClipVertices];
  EXPECT_EQ(clip_triangle(tri, out), 0);
}

TEST(Clip, NearPlaneCrossingKeepsOnlyTheVisiblePart) {
  // Eye space z from -0.5 (in front) to +0.5 (behind); perspective with n = 0.1 maps to clip w = -z_eye.
  const glm::vec4 tri[3] = {{0, 0, 0.3f, 0.5f}, {0.2f, 0, -0.7f, -0.5f}, {0, 0.2f, -0.7f, -0.5f}};
  ClipVertex out[kMaxClipVertices];
  const int n = clip_triangle(tri, out);
  ASSERT_GE(n, 3);
  for (int k = 0; k < n; ++k) {
    EXPECT_GT(out[k].position.w, 0.0f);
    EXPECT_GE(out[k].position.z, -out[k].position.w - 1e-5f);
  }
}

TEST(Clip, NanVerticesAreOutsideEverything) {
  EXPECT_EQ(outcode(glm::vec4(std::nanf(""), 0, 0, 1)), kNonFinite | (kNonFinite - 1));
  EXPECT_TRUE(outcode(glm::vec4(0, INFINITY, 0, 1)) & kNonFinite);
  const glm::vec4 tri[3] = {{std::nanf(""), 0, 0, 1}, {0.5f, 0, 0, 1}, {0, 0.5f, 0, 1}};  // one bad corner
  ClipVertex out[kMaxClipVertices];
  EXPECT_EQ(clip_triangle(tri, out), 0);
}

TEST(Clip, SharedEdgeClipsToIdenticalPoints) {
  // Two triangles share the edge a-b, walked in opposite directions; the clipped points must be bit-identical.
  const glm::vec4 a{-0.5f, 0.3f, 0.2f, 1.0f}, b{3.0f, -0.7f, 0.4f, 1.0f};
  const glm::vec4 first[3] = {a, b, {0.0f, 0.9f, 0.1f, 1.0f}};
  const glm::vec4 second[3] = {b, a, {0.5f, -0.9f, 0.1f, 1.0f}};
  ClipVertex p[kMaxClipVertices], q[kMaxClipVertices];
  const int n = clip_triangle(first, p), m = clip_triangle(second, q);
  int matches = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j)
      if (p[i].position == q[j].position && std::abs(p[i].position.x - 1.0f) < 1e-6f) ++matches;
  EXPECT_EQ(matches, 1);
}

TEST(Clip, LineSegmentsAreTrimmedToTheFrustum) {
  float t0, t1;
  ASSERT_TRUE(clip_line({-2, 0, 0, 1}, {2, 0, 0, 1}, t0, t1));
  EXPECT_NEAR(t0, 0.25f, 1e-6f);
  EXPECT_NEAR(t1, 0.75f, 1e-6f);
  EXPECT_FALSE(clip_line({-2, 0, 0, 1}, {-3, 0, 0, 1}, t0, t1));
  EXPECT_FALSE(clip_line({0, 0, 0, -1}, {0, 0, 0, -2}, t0, t1));
}

}  // namespace
}  // namespace facet::detail::clip_tests
