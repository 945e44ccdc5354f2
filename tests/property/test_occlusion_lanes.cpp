// test_occlusion_lanes.cpp - ambient occlusion's lane stages give the scalar reference's values, bit for bit.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "scene/occlusion_kernel.hpp"

namespace facet::detail::occlusion {
namespace {

// A frame of 203 x 77 pixels (no multiple of a strip) through a perspective camera: a floor one unit below the eye
// receding to the horizon, a wall standing on it three units ahead, a hole where nothing was drawn, and the sky.
struct Frame {
  static constexpr int kWidth = 203, kHeight = 77;
  static constexpr float kWall = -3.0f;  // the wall's view-space z
  glm::mat4 clip_from_view = glm::perspective(0.9f, static_cast<float>(kWidth) / kHeight, 0.1f, 50.0f);
  std::vector<float> depth = std::vector<float>(static_cast<std::size_t>(kWidth) * kHeight, 1.0f);

  float ndc_x(int x) const { return 2.0f * (static_cast<float>(x) + 0.5f) / kWidth - 1.0f; }
  float ndc_y(int y) const { return 1.0f - 2.0f * (static_cast<float>(y) + 0.5f) / kHeight; }
  // The row where the wall meets the floor: view-space y = -1 at the wall's depth.
  int foot() const { return static_cast<int>((1.0f - clip_from_view[1][1] / kWall) * kHeight / 2.0f); }

  Frame() {
    const float p00 = clip_from_view[0][0], p11 = clip_from_view[1][1];
    for (int y = 0; y < kHeight; ++y)
      for (int x = 0; x < kWidth; ++x) {
        float z = 0.0f;  // view-space, 0 for nothing
        if (ndc_y(y) < 0.0f && p11 / ndc_y(y) > -45.0f) z = p11 / ndc_y(y);  // floor: y_view = ndc_y (-z) / p11 = -1
        const float wall_x = ndc_x(x) * -kWall / p00, wall_y = ndc_y(y) * -kWall / p11;
        if (std::abs(wall_x) < 1.0f && wall_y > -1.0f && wall_y < 0.5f && (z == 0.0f || z < kWall)) z = kWall;
        if (x > 160 && x < 170 && y > 66 && y < 72) z = 0.0f;  // the hole
        if (z == 0.0f) continue;
        const glm::vec4 clip = clip_from_view * glm::vec4(0.0f, 0.0f, z, 1.0f);
        depth[static_cast<std::size_t>(y) * kWidth + x] = clip.z / clip.w * 0.5f + 0.5f;
      }
  }
};

// The frame's grids and the sampling over them, the lane stages run as a frame runs them: depth, then openness,
// then the blur, each stage's rows after the previous stage's.
struct Occlusion {
  Frame frame;
  Grid z, raw;
  Spiral spiral;
  Sampling sampling{sized(z), frame.clip_from_view, 0.8f, spiral};
  std::vector<float> open = std::vector<float>(static_cast<std::size_t>(Frame::kWidth) * Frame::kHeight);

  static const Grid& sized(Grid& grid) {
    grid.resize(Frame::kWidth, Frame::kHeight);
    return grid;
  }
  const float* depth(int y) const { return frame.depth.data() + static_cast<std::size_t>(y) * Frame::kWidth; }
  float* open_row(int y) { return open.data() + static_cast<std::size_t>(y) * Frame::kWidth; }
  void run() {
    raw.resize(Frame::kWidth, Frame::kHeight);
    for (int y = 0; y < Frame::kHeight; ++y) depth_row(sampling.unproject, depth(y), Frame::kWidth, z.row(y));
    for (int y = 0; y < Frame::kHeight; ++y) openness_row(sampling, y, raw);
    for (int y = 0; y < Frame::kHeight; ++y) blurred_row(sampling, raw, y, open_row(y));
  }
};

TEST(OcclusionLanes, EveryStageEqualsTheScalarReference) {
  Occlusion o;
  o.run();
  int drawn = 0, occluded = 0;
  for (int y = 0; y < Frame::kHeight; ++y)
    for (int x = 0; x < Frame::kWidth; ++x) {
      ASSERT_EQ(o.z.row(y)[x], o.sampling.unproject.z(o.depth(y)[x])) << x << "," << y;
      const float reference = o.sampling.openness<float>(x, y);
      ASSERT_EQ(o.raw.row(y)[x], reference) << x << "," << y;
      ASSERT_EQ(o.open_row(y)[x], o.sampling.blurred<float>(o.raw, x, y)) << x << "," << y;
      drawn += o.z.row(y)[x] != 0.0f;
      occluded += reference < 0.9f;
    }
  // The frame exercises both outcomes: most of the floor is open, the floor at the wall's foot is not.
  EXPECT_GT(drawn, Frame::kWidth * Frame::kHeight / 2);
  EXPECT_GT(occluded, 50);
}

TEST(OcclusionLanes, TheFloorIsOccludedAtTheWallsFootAndOpenElsewhere) {
  Occlusion o;
  o.run();
  const auto at = [&](int x, int y) { return o.open_row(y)[x]; };
  const int foot = o.frame.foot();
  ASSERT_GT(foot, Frame::kHeight / 2);
  ASSERT_LT(foot + 3, Frame::kHeight);
  EXPECT_EQ(at(10, 5), 1.0f);                  // the sky
  EXPECT_EQ(at(165, 69), 1.0f);                // the hole
  EXPECT_GT(at(101, foot - 15), 0.95f);        // the wall, well above the floor
  EXPECT_LT(at(101, foot + 1), 0.8f);          // the floor at the wall's foot
  EXPECT_GT(at(101, Frame::kHeight - 1), 0.95f);  // the floor near the eye
  EXPECT_GT(at(5, foot + 1), 0.95f);           // the floor beside the wall, at the same depth
}

}  // namespace
}  // namespace facet::detail::occlusion
