// test_occlusion_lanes.cpp - ambient occlusion: lanes equal the scalar reference, a region the whole frame.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <span>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "facet/renderer.hpp"
#include "facet/shaders/stock.hpp"
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
  Sampling sampling{sized(z), frame.clip_from_view, 0.8f, spiral, Window{Frame::kWidth, Frame::kHeight}};
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

// A frame's occlusion over a region that holds every drawn pixel (its origin a multiple of 16 across and 4 down,
// as the frame's is) gives the whole frame's values there, and the whole frame is open outside it.
TEST(OcclusionLanes, ARegionHoldingEveryDrawnPixelGivesTheWholeFramesValues) {
  Occlusion whole;
  // The wall and the floor at its foot: everything outside [37, 180) x [9, height - 3) left undrawn.
  const int x_lo = 37, x_hi = 179, y_lo = 9, y_hi = Frame::kHeight - 4;
  for (int y = 0; y < Frame::kHeight; ++y)
    for (int x = 0; x < Frame::kWidth; ++x)
      if (x < x_lo || x > x_hi || y < y_lo || y > y_hi)
        whole.frame.depth[static_cast<std::size_t>(y) * Frame::kWidth + x] = 1.0f;
  whole.run();

  const Window window{Frame::kWidth, Frame::kHeight, (x_lo - 1) / 16 * 16, (y_lo - 1) / 4 * 4};
  const int width = x_hi + 2 - window.x0, height = std::min(Frame::kHeight, y_hi + 2) - window.y0;
  Grid z, raw;
  z.resize(width, height);
  raw.resize(width, height);
  const Sampling sampling{z, whole.frame.clip_from_view, 0.8f, whole.spiral, window};
  std::vector<float> open(static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
  for (int y = 0; y < height; ++y)
    depth_row(sampling.unproject, whole.depth(window.y0 + y) + window.x0, width, z.row(y));
  for (int y = 0; y < height; ++y) openness_row(sampling, y, raw);
  for (int y = 0; y < height; ++y) blurred_row(sampling, raw, y, open.data() + static_cast<std::size_t>(y) * width);

  int occluded = 0;
  for (int y = 0; y < Frame::kHeight; ++y)
    for (int x = 0; x < Frame::kWidth; ++x) {
      const int rx = x - window.x0, ry = y - window.y0;
      if (rx < 0 || ry < 0 || rx >= width || ry >= height) {
        ASSERT_EQ(whole.open_row(y)[x], 1.0f) << x << "," << y;
        continue;
      }
      ASSERT_EQ(open[static_cast<std::size_t>(ry) * width + rx], whole.open_row(y)[x]) << x << "," << y;
      ASSERT_EQ(raw.row(ry)[rx], whole.raw.row(y)[x]) << x << "," << y;
      occluded += whole.open_row(y)[x] < 0.99f;
    }
  EXPECT_GT(occluded, 0);  // the wall's edges and the hole's rims occlude something
}

// region_of bounds what a depth pass draws: every pixel that random triangles within a box cover, seen from
// cameras around the box and inside it, lies in the region of the box's corners; with the eye inside the box (a
// corner behind it), the region is the whole target.
TEST(OcclusionRegion, HoldsEveryPixelADepthPassDraws) {
  std::mt19937 rng(17);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f), distance(2.5f, 8.0f);
  const glm::vec3 lo(-1.0f, -0.5f, -0.8f), hi(1.0f, 0.5f, 0.8f);
  std::vector<MeshVertex> vertices(600);
  for (MeshVertex& v : vertices)
    v.position = lo + (hi - lo) * (glm::vec3(unit(rng), unit(rng), unit(rng)) * 0.5f + 0.5f);
  std::vector<std::uint32_t> indices(vertices.size());
  for (std::uint32_t i = 0; i < indices.size(); ++i) indices[i] = i;
  constexpr int kW = 160, kH = 96;
  Renderer renderer(2);
  Framebuffer target(kW, kH, 1);
  RenderState two_sided;
  two_sided.cull = CullMode::none;
  int partial = 0, whole = 0, drawn = 0;
  for (int view = 0; view < 40; ++view) {
    const glm::vec3 direction = glm::normalize(glm::vec3(unit(rng), unit(rng) * 0.7f, unit(rng)));
    const glm::vec3 eye = view < 4 ? glm::vec3(unit(rng), unit(rng), unit(rng)) * 0.3f : direction * distance(rng);
    const glm::vec3 looked_at(unit(rng) * 1.5f, unit(rng), unit(rng));
    const glm::mat4 clip_from_world =
        glm::perspective(0.9f, static_cast<float>(kW) / kH, 0.05f, 50.0f) *
        glm::lookAt(eye, looked_at, glm::vec3(0.0f, 1.0f, 0.0f));
    const ClipBox box{clip_from_world, lo, hi};
    const Region region = region_of(std::span<const ClipBox>(&box, 1), kW, kH);
    ASSERT_EQ(region.window.x0 % 16, 0);
    ASSERT_EQ(region.window.y0 % 4, 0);
    renderer.clear(target, glm::vec4(0.0f), 1.0f);
    renderer.draw(target, DepthShader{clip_from_world}, std::span<const MeshVertex>(vertices), indices, two_sided);
    renderer.finish(target);
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x) {
        if (target.depth_at(x, y) >= 1.0f) continue;
        ++drawn;
        ASSERT_TRUE(x >= region.window.x0 && x < region.window.x0 + region.width && y >= region.window.y0 &&
                    y < region.window.y0 + region.height)
            << "view " << view << ": pixel " << x << "," << y << " outside the region from " << region.window.x0
            << "," << region.window.y0 << " of " << region.width << " x " << region.height;
      }
    const bool all = region.width == kW && region.height == kH;
    whole += all, partial += !all;
    EXPECT_TRUE(all || view >= 4) << "view " << view << ": the eye is inside the box";
  }
  EXPECT_GT(partial, 20);  // most views see the box within part of the frame
  EXPECT_GT(drawn, 10000);
  EXPECT_GE(whole, 4);
}

}  // namespace
}  // namespace facet::detail::occlusion
