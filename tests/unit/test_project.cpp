// test_project.cpp - the vectorised projection of vertex blocks agrees bit for bit with project_vertex.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "facet/detail/triangle_setup.hpp"
#include "facet/framebuffer.hpp"
#include "core/setup/project.hpp"

namespace facet::detail::project_tests {
namespace {

void expect_same(const ProjectedVertex& actual, const ProjectedVertex& expected, const glm::vec4& clip) {
  EXPECT_EQ(actual.outcode, expected.outcode) << clip.x << " " << clip.y << " " << clip.z << " " << clip.w;
  EXPECT_EQ(actual.x, expected.x) << clip.x << " " << clip.y << " " << clip.z << " " << clip.w;
  EXPECT_EQ(actual.y, expected.y) << clip.x << " " << clip.y << " " << clip.z << " " << clip.w;
  EXPECT_EQ(std::bit_cast<std::uint32_t>(actual.z), std::bit_cast<std::uint32_t>(expected.z));
  EXPECT_EQ(std::bit_cast<std::uint32_t>(actual.inv_w), std::bit_cast<std::uint32_t>(expected.inv_w));
}

// Projects `clip` in blocks of `block` vertices (the tail block shorter) and checks every vertex.
void check_blocks(const std::vector<glm::vec4>& clip, std::size_t block, int width, int height) {
  ClipBlock positions;
  ProjectedVertex out[kProjectBlock + 1];
  for (std::size_t first = 0; first < clip.size(); first += block) {
    const std::size_t count = std::min(block, clip.size() - first);
    for (std::size_t k = 0; k < count; ++k) {
      const glm::vec4& c = clip[first + k];
      positions.x[k] = c.x, positions.y[k] = c.y, positions.z[k] = c.z, positions.w[k] = c.w;
    }
    const ProjectedVertex sentinel{-7, -7, -7.0f, -7.0f, 0xdeadu};
    std::fill(std::begin(out), std::end(out), sentinel);
    project_vertices(positions, count, out, width, height);
    for (std::size_t k = 0; k < count; ++k)
      expect_same(out[k], project_vertex(clip[first + k], width, height), clip[first + k]);
    EXPECT_EQ(out[count].outcode, sentinel.outcode) << "wrote past the block's count " << count;
  }
}

TEST(ProjectVertices, CentreOfTheViewport) {
  ClipBlock positions;
  positions.x[0] = 0.0f, positions.y[0] = 0.0f, positions.z[0] = 0.0f, positions.w[0] = 1.0f;
  ProjectedVertex out[1];
  project_vertices(positions, 1, out, 1920, 1080);
  EXPECT_EQ(out[0].outcode, 0u);
  EXPECT_EQ(out[0].x, 960 * kSubpixelScale);
  EXPECT_EQ(out[0].y, 540 * kSubpixelScale);
  EXPECT_EQ(out[0].z, 0.5f);
  EXPECT_EQ(out[0].inv_w, 1.0f);
}

TEST(ProjectVertices, HalfwayBetweenSubpixelsRoundsToEven) {
  // Width 2: x = 2^-9 lands at 256.5 sub-pixels, x = 3 * 2^-9 at 257.5; lrint rounds both to the even neighbour.
  ClipBlock positions;
  const float xs[2] = {0.001953125f, 0.005859375f};
  for (int k = 0; k < 2; ++k)
    positions.x[k] = xs[k], positions.y[k] = 0.0f, positions.z[k] = 0.0f, positions.w[k] = 1.0f;
  ProjectedVertex out[2];
  project_vertices(positions, 2, out, 2, 2);
  EXPECT_EQ(out[0].x, 256);
  EXPECT_EQ(out[1].x, 258);
}

TEST(ProjectVertices, OutsideOrNonFiniteKeepsOnlyTheOutcode) {
  const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
  const std::vector<glm::vec4> clip = {{0, 0, 0, -1},  {2, 0, 0, 1}, {0, 0, -3, 1},    {nan, 0, 0, 1},
                                       {0, inf, 0, 1}, {0, 0, 0, 0}, {0, 0, 0, 1e-6f}, {0, 0, 0, nan}};
  ClipBlock positions;
  for (std::size_t k = 0; k < clip.size(); ++k)
    positions.x[k] = clip[k].x, positions.y[k] = clip[k].y, positions.z[k] = clip[k].z, positions.w[k] = clip[k].w;
  ProjectedVertex out[8];
  project_vertices(positions, clip.size(), out, 640, 480);
  for (std::size_t k = 0; k < clip.size(); ++k) {
    EXPECT_NE(out[k].outcode, 0u) << k;
    EXPECT_EQ(out[k].x, 0) << k;
    EXPECT_EQ(out[k].inv_w, 0.0f) << k;
  }
  EXPECT_EQ(out[3].outcode & kNonFinite, kNonFinite);
  EXPECT_EQ(out[1].outcode & kNonFinite, 0u);
  check_blocks(clip, 3, 640, 480);
}

// Positions inside, on and outside every plane, near the eye, far beyond the target (the snap clamps them), and
// non-finite, at every block length and several target sizes, including the largest.
TEST(ProjectVertices, AgreesWithProjectVertexEverywhere) {
  std::mt19937 rng(20261123);
  std::uniform_real_distribution<float> unit(-1.3f, 1.3f), w_range(-0.5f, 40.0f), wide(-1e6f, 1e6f);
  const float specials[] = {0.0f,
                            -0.0f,
                            1.0f,
                            -1.0f,
                            1e-5f,
                            1e30f,
                            -1e30f,
                            std::numeric_limits<float>::infinity(),
                            std::numeric_limits<float>::quiet_NaN(),
                            std::numeric_limits<float>::denorm_min()};
  std::vector<glm::vec4> clip;
  for (int i = 0; i < 4000; ++i) {
    const float w = w_range(rng);
    glm::vec4 c(unit(rng) * w, unit(rng) * w, unit(rng) * w, w);
    if (i % 7 == 0) c[static_cast<int>(rng() % 4)] = specials[rng() % std::size(specials)];
    if (i % 11 == 0) c.x = wide(rng);
    clip.push_back(c);
  }
  const int sizes[][2] = {{1920, 1080}, {1, 1}, {333, 77}, {kMaxDimension, kMaxDimension}};
  for (const auto& size : sizes)
    for (const std::size_t block : {std::size_t{1}, std::size_t{15}, std::size_t{16}, std::size_t{17}, kProjectBlock})
      check_blocks(clip, block, size[0], size[1]);
}

}  // namespace
}  // namespace facet::detail::project_tests
