// test_coverage.cpp - watertightness and the fill rule: tilings cover each pixel once, closed meshes twice.
#include <gtest/gtest.h>

#include <algorithm>
#include <glm/gtc/matrix_transform.hpp>

#include "facet/detail/raster.hpp"
#include "support/draw_helpers.hpp"

namespace facet::test {
namespace {

struct GridCase {
  int width, height, cells_x, cells_y;
  bool random_w;
};

class JitteredGridTest : public ::testing::TestWithParam<GridCase> {};

TEST_P(JitteredGridTest, CoversEveryPixelExactlyOnce) {
  const GridCase c = GetParam();
  for (std::uint32_t seed = 1; seed <= 12; ++seed) {
    const ClipMesh grid = jittered_grid(c.cells_x, c.cells_y, seed * 7919u + c.width, c.random_w);
    const std::vector<int> counts = coverage_counts(grid, c.width, c.height, no_depth_no_cull());
    int wrong = 0;
    for (int y = 0; y < c.height; ++y)
      for (int x = 0; x < c.width; ++x)
        if (counts[static_cast<std::size_t>(y) * c.width + x] != 1 && wrong++ < 5)
          ADD_FAILURE() << "seed " << seed << ": pixel (" << x << ", " << y << ") covered "
                        << counts[static_cast<std::size_t>(y) * c.width + x] << " times";
    ASSERT_EQ(wrong, 0) << "seed " << seed;
  }
}

INSTANTIATE_TEST_SUITE_P(OddSizes, JitteredGridTest,
                         ::testing::Values(GridCase{37, 23, 5, 4, false}, GridCase{101, 67, 13, 9, false},
                                           GridCase{129, 65, 17, 11, true}, GridCase{203, 131, 40, 25, true},
                                           GridCase{7, 5, 9, 8, true}));

TEST(Coverage, ClosedMeshWithoutCullingCoversInteriorTwice) {
  const int width = 161, height = 121;
  const glm::mat4 clip_from_object = glm::perspective(glm::radians(50.0f), float(width) / height, 0.1f, 10.0f) *
                                     glm::lookAt(glm::vec3(0.4f, 0.9f, 2.6f), glm::vec3(0), glm::vec3(0, 1, 0));
  const ClipMesh sphere = closed_sphere(23, 37, clip_from_object);
  const std::vector<int> counts = coverage_counts(sphere, width, height, no_depth_no_cull());
  int twice = 0;
  for (const int n : counts) {
    ASSERT_TRUE(n == 0 || n == 2) << "a pixel was covered " << n << " times";
    twice += n == 2;
  }
  EXPECT_GT(twice, width * height / 5);

  RenderState cull_back = no_depth_no_cull();
  cull_back.cull = CullMode::back;
  const std::vector<int> front = coverage_counts(sphere, width, height, cull_back);
  cull_back.cull = CullMode::front;
  const std::vector<int> back = coverage_counts(sphere, width, height, cull_back);
  for (std::size_t i = 0; i < counts.size(); ++i) {
    ASSERT_EQ(front[i], counts[i] / 2) << "front faces alone must cover the silhouette once";
    ASSERT_EQ(back[i], counts[i] / 2) << "back faces alone must cover the silhouette once";
  }
}

// Maps a pixel-space point (x right, y down, pixel centres at +0.5) of an 8x8 target to clip space.
glm::vec4 pixel_point(float x, float y) { return {x / 4.0f - 1.0f, 1.0f - y / 4.0f, 0.0f, 1.0f}; }

std::vector<int> cover_one(glm::vec2 a, glm::vec2 b, glm::vec2 c) {
  ClipMesh m;
  m.clip = {pixel_point(a.x, a.y), pixel_point(b.x, b.y), pixel_point(c.x, c.y)};
  m.color.assign(3, glm::vec3(1));
  m.indices = {0, 1, 2};
  return coverage_counts(m, 8, 8, no_depth_no_cull());
}

TEST(FillRule, TopAndLeftEdgesAreInsideBottomAndRightAreNot) {
  // Upper-left half of the square between pixel centres (1.5, 1.5) and (5.5, 5.5): its top edge (y = 1.5) and
  // left edge (x = 1.5) pass through pixel centres and own them; the diagonal is its bottom-right edge.
  for (const bool reverse : {false, true}) {
    const std::vector<int> upper = reverse ? cover_one({1.5f, 1.5f}, {1.5f, 5.5f}, {5.5f, 1.5f})
                                           : cover_one({1.5f, 1.5f}, {5.5f, 1.5f}, {1.5f, 5.5f});
    for (int y = 0; y < 8; ++y)
      for (int x = 0; x < 8; ++x) {
        const bool expected = x >= 1 && y >= 1 && x + y < 6;
        EXPECT_EQ(upper[y * 8 + x], expected ? 1 : 0) << "pixel (" << x << ", " << y << "), reversed " << reverse;
      }
  }
  // The lower-right half owns the diagonal; its right (x = 5.5) and bottom (y = 5.5) edges are excluded.
  const std::vector<int> lower = cover_one({5.5f, 1.5f}, {5.5f, 5.5f}, {1.5f, 5.5f});
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) {
      const bool expected = x <= 4 && y <= 4 && x + y >= 6;
      EXPECT_EQ(lower[y * 8 + x], expected ? 1 : 0) << "pixel (" << x << ", " << y << ")";
    }
}

TEST(FillRule, VertexOnAPixelCentreBelongsToOneOfFourTriangles) {
  // Four triangles around the pixel centre (3.5, 3.5): exactly one covers it.
  const glm::vec2 c(3.5f, 3.5f);
  const glm::vec2 ring[4] = {{1.0f, 1.0f}, {6.0f, 1.0f}, {6.0f, 6.0f}, {1.0f, 6.0f}};
  int owners = 0;
  for (int k = 0; k < 4; ++k) owners += cover_one(c, ring[k], ring[(k + 1) % 4])[3 * 8 + 3];
  EXPECT_EQ(owners, 1);
}

TEST(Coverage, ZeroAreaAndOffscreenTrianglesDrawNothing) {
  const std::vector<int> line = cover_one({1.5f, 1.5f}, {5.5f, 5.5f}, {3.5f, 3.5f});
  EXPECT_EQ(std::count(line.begin(), line.end(), 0), 64);
  const std::vector<int> away = cover_one({20.0f, 1.0f}, {30.0f, 1.0f}, {20.0f, 9.0f});
  EXPECT_EQ(std::count(away.begin(), away.end(), 0), 64);
}

}  // namespace
}  // namespace facet::test

namespace facet::test {
namespace {

ClipMesh eye_space_mesh(const glm::mat4& projection, std::initializer_list<glm::vec3> points,
                        std::vector<std::uint32_t> indices) {
  ClipMesh m;
  for (const glm::vec3& p : points) {
    m.clip.push_back(projection * glm::vec4(p, 1.0f));
    m.color.emplace_back(1.0f);
  }
  m.indices = std::move(indices);
  return m;
}

TEST(Clipping, TriangleCrossingTheNearPlaneDrawsExactlyItsVisiblePart) {
  // Eye space: A and B in front, C behind the eye. With near = 0.5 the visible part is the quad A B Q P, where P
  // and Q are where AC and BC meet z = -0.5 (halfway along each edge).
  const glm::mat4 projection = glm::perspective(glm::radians(90.0f), 1.0f, 0.5f, 10.0f);
  const glm::vec3 a(-1, -1, -2), b(1, -1, -2), c(0, 1, 1), p(-0.5f, 0, -0.5f), q(0.5f, 0, -0.5f);
  const ClipMesh crossing = eye_space_mesh(projection, {a, b, c}, {0, 1, 2});
  const ClipMesh visible = eye_space_mesh(projection, {a, b, q, p}, {0, 1, 2, 0, 2, 3});
  const std::vector<int> drawn = coverage_counts(crossing, 97, 97, no_depth_no_cull());
  const std::vector<int> expected = coverage_counts(visible, 97, 97, no_depth_no_cull());
  int covered = 0, different = 0;
  for (std::size_t i = 0; i < drawn.size(); ++i) {
    ASSERT_LE(drawn[i], 1);
    covered += drawn[i];
    different += drawn[i] != expected[i];
  }
  EXPECT_GT(covered, 97 * 97 / 8);
  EXPECT_LE(different, 3) << "only pixels on the cut edge may differ (its end points are rounded differently)";
}

TEST(Clipping, TriangleBehindTheCameraDrawsNothing) {
  const glm::mat4 projection = glm::perspective(glm::radians(90.0f), 1.0f, 0.5f, 10.0f);
  const ClipMesh behind = eye_space_mesh(projection, {{-1, -1, 2}, {1, -1, 2}, {0, 1, 3}}, {0, 1, 2});
  const std::vector<int> drawn = coverage_counts(behind, 64, 64, no_depth_no_cull());
  EXPECT_EQ(std::count(drawn.begin(), drawn.end(), 0), 64 * 64);
}

// The block walk's rectangle masks, against the definition: bit j * 8 + i for each pixel of the rectangle.
TEST(BlockRectMask, HasExactlyTheRectanglesPixels) {
  for (int i0 = 0; i0 < 8; ++i0)
    for (int i1 = i0; i1 < 8; ++i1)
      for (int j0 = 0; j0 < 8; ++j0)
        for (int j1 = j0; j1 < 8; ++j1) {
          std::uint64_t expected = 0;
          for (int j = j0; j <= j1; ++j)
            for (int i = i0; i <= i1; ++i) expected |= std::uint64_t{1} << (j * 8 + i);
          ASSERT_EQ(detail::block_rect_mask(i0, i1, j0, j1), expected) << i0 << ".." << i1 << " x " << j0 << ".." << j1;
        }
}

}  // namespace
}  // namespace facet::test
