// test_points.cpp - Renderer::draw_points: the pixels a point covers, its depth against triangles, and determinism.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "facet/renderer.hpp"
#include "support/image_asserts.hpp"
#include "support/test_shaders.hpp"

namespace facet::test {
namespace {

constexpr int kWidth = 64, kHeight = 48;
constexpr std::uint32_t kBlack = 0xff000000u, kWhite = 0xffffffffu;

// The clip position of window point (x, y) (pixels, y down, as pixel centres are (i + 0.5, j + 0.5)) at depth z.
glm::vec4 clip_at(float x, float y, float z = 0.0f) {
  return {2.0f * x / kWidth - 1.0f, 1.0f - 2.0f * y / kHeight, z, 1.0f};
}

struct Drawn {
  std::vector<std::uint32_t> pixels;
  DrawStats stats;
};

Drawn draw_points(const std::vector<ColorShader::Vertex>& points, const RenderState& state, int threads = 1,
                  int samples = 1) {
  Framebuffer target(kWidth, kHeight, samples);
  Renderer renderer(threads);
  renderer.clear(target, glm::vec4(0, 0, 0, 1), 1.0f);
  std::vector<std::uint32_t> indices(points.size());
  for (std::uint32_t i = 0; i < indices.size(); ++i) indices[i] = i;
  renderer.draw_points(target, ColorShader{}, std::span<const ColorShader::Vertex>(points), indices, state);
  renderer.finish(target);
  return {{target.color().begin(), target.color().end()}, renderer.last_stats()};
}

RenderState point_state(float size, PointShape shape = PointShape::square) {
  RenderState state;
  state.point_size = size;
  state.point_shape = shape;
  return state;
}

// Within 1/64 pixel of a pixel centre, either way: snapping to 1/256 pixel may put such an edge on either side.
bool near_centre_line(float edge) {
  const float d = std::abs(edge - 0.5f - std::round(edge - 0.5f));
  return d < 1.0f / 64.0f;
}

TEST(Points, ASquareCoversThePixelCentresWithinIt) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> x(4.0f, kWidth - 4.0f), y(4.0f, kHeight - 4.0f);
  int checked = 0;
  for (const float size : {1.0f, 2.0f, 3.0f, 4.5f, 7.25f}) {
    for (int trial = 0; trial < 40; ++trial) {
      const float cx = x(rng), cy = y(rng), half = size * 0.5f;
      if (near_centre_line(cx - half) || near_centre_line(cx + half) || near_centre_line(cy - half) ||
          near_centre_line(cy + half))
        continue;
      const Drawn drawn = draw_points({{clip_at(cx, cy), glm::vec3(1.0f)}}, point_state(size));
      int covered = 0;
      for (int j = 0; j < kHeight; ++j)
        for (int i = 0; i < kWidth; ++i) {
          const float px = static_cast<float>(i) + 0.5f, py = static_cast<float>(j) + 0.5f;
          const bool inside = std::abs(px - cx) < half && std::abs(py - cy) < half;
          const std::uint32_t pixel = drawn.pixels[static_cast<std::size_t>(j) * kWidth + i];
          ASSERT_EQ(pixel, inside ? kWhite : kBlack)
              << "size " << size << " at (" << cx << ", " << cy << "), pixel (" << i << ", " << j << ")";
          covered += inside;
        }
      EXPECT_GT(covered, 0);
      ++checked;
    }
  }
  EXPECT_GT(checked, 150);
}

// A point sized by depth (RenderState::point_size_per_w) covers exactly what a point of point_size_per_w / w pixels
// does, w its clip w, for squares and discs, and clamps to kMinScaledPointSize..kMaxPointSize.
TEST(Points, APointSizedByDepthCoversWhatItsSizeAtThatDepthWould) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> x(6.0f, kWidth - 6.0f), y(6.0f, kHeight - 6.0f), w(0.5f, 4.0f);
  for (const PointShape shape : {PointShape::square, PointShape::disc})
    for (int trial = 0; trial < 30; ++trial) {
      const float cx = x(rng), cy = y(rng), depth = w(rng), per_w = trial == 0 ? 1e-4f : trial == 1 ? 1e4f : 6.0f;
      const glm::vec4 clip = clip_at(cx, cy) * depth;  // the same window position, at clip w = depth
      RenderState by_depth = point_state(1.0f, shape);
      by_depth.point_size_per_w = per_w;
      const float size = std::clamp(per_w / depth, kMinScaledPointSize, kMaxPointSize);
      const Drawn scaled = draw_points({{clip, glm::vec3(1.0f)}}, by_depth);
      const Drawn fixed = draw_points({{clip, glm::vec3(1.0f)}}, point_state(size, shape));
      ASSERT_EQ(scaled.pixels, fixed.pixels) << "per_w " << per_w << " at w " << depth << ", shape "
                                             << static_cast<int>(shape);
    }
}

TEST(Points, ADiscCoversTheCentresWithinItsRadius) {
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> x(10.0f, kWidth - 10.0f), y(10.0f, kHeight - 10.0f);
  for (const float size : {3.0f, 6.0f, 12.5f}) {
    for (int trial = 0; trial < 20; ++trial) {
      const float cx = x(rng), cy = y(rng), r = size * 0.5f;
      const Drawn drawn = draw_points({{clip_at(cx, cy), glm::vec3(1.0f)}}, point_state(size, PointShape::disc));
      int inside = 0, outside_square_corners = 0;
      for (int j = 0; j < kHeight; ++j)
        for (int i = 0; i < kWidth; ++i) {
          const float d = std::hypot(static_cast<float>(i) + 0.5f - cx, static_cast<float>(j) + 0.5f - cy);
          const std::uint32_t pixel = drawn.pixels[static_cast<std::size_t>(j) * kWidth + i];
          // The polygon stays within a tenth of a pixel inside the circle (and snapping moves it 1/256 more).
          if (d < r - 0.11f) {
            EXPECT_EQ(pixel, kWhite) << "size " << size << ", distance " << d;
          }
          if (d > r) {
            EXPECT_EQ(pixel, kBlack) << "size " << size << ", distance " << d;
          }
          inside += d < r - 0.11f;
          // A disc leaves out the square's corners that its circle misses.
          outside_square_corners += d > r && std::abs(static_cast<float>(i) + 0.5f - cx) < r &&
                                    std::abs(static_cast<float>(j) + 0.5f - cy) < r;
        }
      EXPECT_GT(inside, 0);
      if (size > 6.0f) {
        EXPECT_GT(outside_square_corners, 0);
      }
    }
  }
}

TEST(Points, EachPixelTakesThePointsColourAndDepthTestsAgainstTriangles) {
  // A red triangle over the whole target at depth 0 (window 0.5); a green point in front, a blue one behind.
  Framebuffer target(kWidth, kHeight);
  Renderer renderer(2);
  renderer.clear(target, glm::vec4(0, 0, 0, 1), 1.0f);
  const std::vector<ColorShader::Vertex> cover = {{{-1, -1, 0, 1}, {1, 0, 0}}, {{3, -1, 0, 1}, {1, 0, 0}},
                                                  {{-1, 3, 0, 1}, {1, 0, 0}}};
  const std::vector<std::uint32_t> triangle = {0, 1, 2};
  renderer.draw(target, ColorShader{}, std::span<const ColorShader::Vertex>(cover), triangle);
  const std::vector<ColorShader::Vertex> points = {{clip_at(20.3f, 20.3f, -0.5f), {0, 1, 0}},
                                                   {clip_at(40.3f, 20.3f, 0.5f), {0, 0, 1}}};
  const std::vector<std::uint32_t> both = {0, 1};
  renderer.draw_points(target, ColorShader{}, std::span<const ColorShader::Vertex>(points), both, point_state(3.0f));
  renderer.finish(target);
  EXPECT_EQ(target.pixel(20, 20), 0xff00ff00u);  // in front: green
  EXPECT_EQ(target.pixel(40, 20), 0xff0000ffu);  // behind: the red triangle
  EXPECT_FLOAT_EQ(target.depth_at(20, 20), 0.25f);  // the point's window depth, (z / w + 1) / 2
  EXPECT_FLOAT_EQ(target.depth_at(40, 20), 0.5f);
}

TEST(Points, OnlyPointsInsideTheViewVolumeDrawAndBadIndicesAreSkipped) {
  // As OpenGL clips points by position: one just inside the left edge keeps its on-screen pixels, one just outside
  // draws nothing even though its square would reach the screen; one behind the far plane is culled too.
  const std::vector<ColorShader::Vertex> points = {{clip_at(0.75f, 10.5f), glm::vec3(1.0f)},
                                                   {clip_at(-0.25f, 30.5f), glm::vec3(1.0f)},
                                                   {clip_at(30.5f, 30.5f, 1.5f), glm::vec3(1.0f)}};
  Framebuffer target(kWidth, kHeight);
  Renderer renderer(1);
  renderer.clear(target, glm::vec4(0, 0, 0, 1), 1.0f);
  const std::vector<std::uint32_t> indices = {0, 1, 2, 7};
  renderer.draw_points(target, ColorShader{}, std::span<const ColorShader::Vertex>(points), indices,
                       point_state(5.0f));
  renderer.finish(target);
  EXPECT_EQ(renderer.last_stats().primitives, 4u);
  EXPECT_EQ(renderer.last_stats().invalid, 1u);
  EXPECT_EQ(renderer.last_stats().culled, 2u);
  EXPECT_EQ(target.pixel(0, 10), kWhite);
  EXPECT_EQ(target.pixel(2, 10), kWhite);
  EXPECT_EQ(target.pixel(3, 10), kBlack);
  EXPECT_EQ(target.pixel(0, 30), kBlack);
  EXPECT_EQ(target.pixel(1, 30), kBlack);
  EXPECT_EQ(target.pixel(30, 30), kBlack);
}

TEST(Points, TheImageIsTheSameAtAnyThreadCountAndSampleCount) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> x(-2.0f, kWidth + 2.0f), y(-2.0f, kHeight + 2.0f), z(-0.9f, 0.9f), c(0, 1);
  std::vector<ColorShader::Vertex> points(3000);
  for (auto& p : points) p = {clip_at(x(rng), y(rng), z(rng)), glm::vec3(c(rng), c(rng), c(rng))};
  for (const PointShape shape : {PointShape::square, PointShape::disc})
    for (const int samples : {1, 4}) {
      const Drawn one = draw_points(points, point_state(2.5f, shape), 1, samples);
      for (const int threads : {2, 4}) {
        const Drawn many = draw_points(points, point_state(2.5f, shape), threads, samples);
        EXPECT_EQ(one.pixels, many.pixels) << threads << " threads, " << samples << " samples";
      }
    }
}

// Deferred shading's visibility pass takes small squares pixel by pixel (raster_visibility.cpp); immediate shading
// takes every square through the triangles' block coverage. Both give the same colours and depths, for squares
// below and above that size, under each depth function, with and without depth writes, at 1 and 4 samples.
TEST(Points, DeferredAndImmediateShadingAgreeForSquaresOfEverySize) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> x(-4.0f, kWidth + 4.0f), y(-4.0f, kHeight + 4.0f), z(-0.9f, 0.9f), c(0, 1);
  std::vector<ColorShader::Vertex> points(1500);
  for (auto& p : points) p = {clip_at(x(rng), y(rng), z(rng)), glm::vec3(c(rng), c(rng), c(rng))};
  std::vector<std::uint32_t> indices(points.size());
  for (std::uint32_t i = 0; i < indices.size(); ++i) indices[i] = i;
  const auto draw = [&](RenderState state, bool deferred, int samples) {
    Framebuffer target(kWidth, kHeight, samples);
    Renderer renderer(2);
    renderer.clear(target, glm::vec4(0, 0, 0, 1), 0.5f);  // GREATER and LESS both pass somewhere
    state.defer_shading = deferred;
    renderer.draw_points(target, ColorShader{}, std::span<const ColorShader::Vertex>(points), indices, state);
    renderer.finish(target);
    return std::pair{std::vector<std::uint32_t>(target.color().begin(), target.color().end()),
                     std::vector<float>(target.depth().begin(), target.depth().end())};
  };
  int differing = 0;
  for (const float size : {1.0f, 2.0f, 2.5f, 7.5f, 12.0f})
    for (const DepthFunc func : {DepthFunc::less, DepthFunc::lequal, DepthFunc::greater, DepthFunc::notequal,
                                 DepthFunc::always})
      for (const bool write : {true, false})
        for (const int samples : {1, 4}) {
          RenderState state = point_state(size);
          state.depth_func = func;
          state.depth_write = write;
          const auto deferred = draw(state, true, samples), immediate = draw(state, false, samples);
          ASSERT_EQ(deferred.first, immediate.first)
              << "size " << size << ", function " << static_cast<int>(func) << ", writes " << write << ", samples "
              << samples;
          ASSERT_EQ(deferred.second, immediate.second) << "size " << size << ", function " << static_cast<int>(func);
          differing += deferred.first != draw(point_state(size), true, samples).first;
        }
  EXPECT_GT(differing, 0);  // the depth functions draw different pictures
}

TEST(Points, MultisamplingCoversWholePixelsInsideAndBlendsTheEdges) {
  // A 3-pixel square at a pixel corner: 3x3 pixels fully inside at 4 samples take the whole colour; the ring
  // around it is partly covered.
  const Drawn drawn = draw_points({{clip_at(20.25f, 20.25f), glm::vec3(1.0f)}}, point_state(3.5f), 1, 4);
  for (int j = 19; j <= 21; ++j)
    for (int i = 19; i <= 21; ++i) EXPECT_EQ(drawn.pixels[static_cast<std::size_t>(j) * kWidth + i], kWhite);
  int partial = 0;
  for (const std::uint32_t p : drawn.pixels) partial += p != kWhite && p != kBlack;
  EXPECT_GT(partial, 0);
}

// Small squares at 4 samples, sample by sample: a sample is covered when its position lies within the square
// ([left, right) x [top, bottom), the fill rule's sides). A square's edges pass everywhere: each sample's own bounds
// (at_sample) shape it, which are often a pixel narrower than the square's bounds over all samples. Squares whose
// sides lie within 1/32 pixel of a sample, where snapping decides, are left out.
TEST(Points, SmallSquaresCoverTheSamplesWithinThem) {
  constexpr int kSamples = 4;
  // Vulkan's standard 4-sample positions, in 1/16 pixel from the pixel's top-left corner.
  constexpr int kAt[kSamples][2] = {{6, 2}, {14, 6}, {2, 10}, {10, 14}};
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> x(4.0f, kWidth - 4.0f), y(4.0f, kHeight - 4.0f);
  int checked = 0, covered = 0;
  for (const float size : {1.0f, 1.5f}) {
    for (int trial = 0; trial < 100; ++trial) {
      const float cx = x(rng), cy = y(rng);
      const float left = cx - size / 2, right = cx + size / 2, top = cy - size / 2, bottom = cy + size / 2;
      const auto near_a_sample = [&](float side, int axis) {
        for (int p = -8; p <= kWidth + 8; ++p)
          for (const auto& at : kAt)
            if (std::abs(side - (static_cast<float>(p) + static_cast<float>(at[axis]) / 16.0f)) < 1.0f / 32.0f) return true;
        return false;
      };
      if (near_a_sample(left, 0) || near_a_sample(right, 0) || near_a_sample(top, 1) || near_a_sample(bottom, 1))
        continue;
      Framebuffer target(kWidth, kHeight, kSamples);
      target.keep_samples(true);
      Renderer renderer(1);
      renderer.clear(target, glm::vec4(0, 0, 0, 1), 1.0f);
      const std::vector<ColorShader::Vertex> point{{clip_at(cx, cy), glm::vec3(1.0f)}};
      const std::vector<std::uint32_t> index{0};
      renderer.draw_points(target, ColorShader{}, std::span<const ColorShader::Vertex>(point), index,
                           point_state(size));
      renderer.finish(target);
      for (int s = 0; s < kSamples; ++s) {
        const std::span<const std::uint32_t> plane = target.sample_color(s);
        for (int j = 0; j < kHeight; ++j)
          for (int i = 0; i < kWidth; ++i) {
            const float sx = static_cast<float>(i) + static_cast<float>(kAt[s][0]) / 16.0f;
            const float sy = static_cast<float>(j) + static_cast<float>(kAt[s][1]) / 16.0f;
            const bool inside = sx >= left && sx < right && sy >= top && sy < bottom;
            ASSERT_EQ(plane[static_cast<std::size_t>(j) * kWidth + i], inside ? kWhite : kBlack)
                << "size " << size << " at " << cx << ", " << cy << ": sample " << s << " of pixel " << i << ", " << j;
            covered += inside;
          }
      }
      ++checked;
    }
  }
  EXPECT_GT(checked, 80);
  EXPECT_GT(covered, 4 * checked);  // a 1-pixel square covers 4 samples, a 1.5-pixel one 4 to 9
}

}  // namespace
}  // namespace facet::test
