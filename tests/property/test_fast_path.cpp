// test_fast_path.cpp - the tiled, threaded rasterizer against the scalar reference, and against itself per thread
// count.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <glm/gtc/matrix_transform.hpp>

#include "support/draw_helpers.hpp"

namespace facet::test {
namespace {

struct Difference {
  std::size_t pixels_over = 0;  // pixels whose largest channel difference exceeds the tolerance
  int max_channel = 0;
};

Difference compare(const Framebuffer& a, const Framebuffer& b, int tolerance) {
  Difference d;
  for (std::size_t i = 0; i < a.color().size(); ++i) {
    int worst = 0;
    for (int c = 0; c < 4; ++c)
      worst = std::max(worst, std::abs(int((a.color()[i] >> (8 * c)) & 0xff) - int((b.color()[i] >> (8 * c)) & 0xff)));
    d.max_channel = std::max(d.max_channel, worst);
    d.pixels_over += worst > tolerance;
  }
  return d;
}

ClipMesh perspective_sphere(int width, int height, int stacks, int slices) {
  const glm::mat4 clip_from_object = glm::perspective(glm::radians(45.0f), float(width) / height, 0.1f, 10.0f) *
                                     glm::lookAt(glm::vec3(0.3f, 0.5f, 2.2f), glm::vec3(0), glm::vec3(0, 1, 0));
  return closed_sphere(stacks, slices, clip_from_object);
}

// Coverage is exact integer arithmetic in both rasterizers, so the pixels each triangle covers must be identical.
TEST(FastPath, CoverageEqualsReferenceExactly) {
  const RenderState state = no_depth_no_cull();
  const ClipMesh scenes[] = {triangle_soup(300, 5), jittered_grid(11, 7, 3, true), perspective_sphere(173, 97, 17, 29)};
  for (const ClipMesh& scene : scenes) {
    const std::vector<int> fast = coverage_counts(scene, 173, 97, state, 2, false);
    const std::vector<int> slow = coverage_counts(scene, 173, 97, state, 1, true);
    ASSERT_EQ(fast, slow);
  }
}

// Colours come from different (plane vs barycentric) float evaluations, so allow one level of rounding; with the
// depth test on, a handful of pixels where two surfaces meet may also pick the other surface.
TEST(FastPath, ImageEqualsReferenceWithinTolerance) {
  RenderState culled;  // back-face culling, depth LESS
  RenderState depth_no_cull;
  depth_no_cull.cull = CullMode::none;
  const struct {
    ClipMesh mesh;
    RenderState state;
  } scenes[] = {{triangle_soup(400, 11), depth_no_cull},
                {perspective_sphere(211, 143, 31, 47), culled},
                {perspective_sphere(211, 143, 9, 13), depth_no_cull},
                {jittered_grid(9, 6, 8, true), no_depth_no_cull()}};
  for (const auto& scene : scenes) {
    const Framebuffer fast = render_colors(scene.mesh, 211, 143, scene.state, 3);
    const Framebuffer slow = render_colors(scene.mesh, 211, 143, scene.state, 1, true);
    const Difference d = compare(fast, slow, 1);
    EXPECT_LE(d.pixels_over, 211u * 143u / 1000u) << "max channel difference " << d.max_channel;
  }
}

TEST(FastPath, IdenticalAtAnyThreadCount) {
  // Enough triangles for several setup chunks and a target of many tiles, so both are actually split.
  RenderState depth_no_cull;
  depth_no_cull.cull = CullMode::none;
  const ClipMesh sphere = perspective_sphere(517, 301, 90, 130);
  ClipMesh soup = triangle_soup(6000, 17);
  const Framebuffer one = render_colors(sphere, 517, 301, RenderState{}, 1);
  const Framebuffer soup_one = render_colors(soup, 517, 301, depth_no_cull, 1);
  for (const int threads : {2, 3, 8}) {
    const Framebuffer many = render_colors(sphere, 517, 301, RenderState{}, threads);
    EXPECT_TRUE(std::equal(one.color().begin(), one.color().end(), many.color().begin())) << threads << " threads";
    EXPECT_TRUE(std::equal(one.depth().begin(), one.depth().end(), many.depth().begin())) << threads << " threads";
    const Framebuffer soup_many = render_colors(soup, 517, 301, depth_no_cull, threads);
    EXPECT_TRUE(std::equal(soup_one.color().begin(), soup_one.color().end(), soup_many.color().begin()))
        << threads << " threads";
  }
}

// The painter's order is sorted per tile in the tile pass; each tile must see its triangles in the order a sort of
// the whole draw gives (depth key descending, ties in index order), as the reference sorts them: over several setup
// chunks, with triangles clipped into pieces, and with copies of triangles (equal keys) in other colours, where
// index order decides. Coverage is exact, so with the order right every pixel is the same triangle's colour.
TEST(FastPath, PainterOrderSortedPerTileMatchesTheWholeDrawSort) {
  ClipMesh soup = triangle_soup(5000, 29);
  for (std::uint32_t t = 0; t < 600; t += 3) {  // copies drawn later, in other colours
    for (int k = 0; k < 3; ++k) {
      soup.clip.push_back(soup.clip[soup.indices[3 * t + k]]);
      soup.color.emplace_back(1.0f - soup.color[soup.indices[3 * t + k]]);
      soup.indices.push_back(static_cast<std::uint32_t>(soup.clip.size() - 1));
    }
  }
  RenderState painter = no_depth_no_cull();
  painter.order = DrawOrder::back_to_front;
  const Framebuffer slow = render_colors(soup, 173, 97, painter, 1, true);
  const Framebuffer one = render_colors(soup, 173, 97, painter, 1);
  const Difference d = compare(one, slow, 1);
  EXPECT_EQ(d.pixels_over, 0u) << "max channel difference " << d.max_channel;
  for (const int threads : {2, 3}) {
    const Framebuffer many = render_colors(soup, 173, 97, painter, threads);
    EXPECT_TRUE(std::ranges::equal(many.color(), one.color())) << threads << " threads";
  }
}

// Draws in the painter's order that follow each other are composited together per tile: two meshes of tilted,
// shifted layers whose depths interleave come out as one draw of both does (ties in draw order, as in index order),
// not as the second mesh painted over the first; at 1 and 4 samples, on 1 to 3 threads.
TEST(FastPath, ConsecutivePainterDrawsCompositeTogether) {
  const int width = 150, height = 110;
  const glm::mat4 proj = glm::perspective(glm::radians(60.0f), float(width) / height, 0.1f, 20.0f);
  ClipMesh layers[2], both;
  for (int i = 0; i < 6; ++i) {
    ClipMesh& m = layers[i % 2];
    const float z = -2.0f - 0.7f * i, shift = 0.25f * i - 0.6f;
    for (const glm::vec2 c : {glm::vec2(-1, -1), glm::vec2(1, -1), glm::vec2(1, 1), glm::vec2(-1, 1)}) {
      m.clip.push_back(proj * glm::vec4(c * 1.4f + glm::vec2(shift, 0.1f * i), z + 0.8f * c.x, 1));
      m.color.emplace_back(0.15f * i, 1.0f - 0.15f * i, i % 2 ? 0.9f : 0.1f);
    }
    const auto b = static_cast<std::uint32_t>(m.clip.size() - 4);
    m.indices.insert(m.indices.end(), {b, b + 1, b + 2, b, b + 2, b + 3});
  }
  both = layers[0];
  const auto offset = static_cast<std::uint32_t>(both.clip.size());
  for (const std::uint32_t i : layers[1].indices) both.indices.push_back(i + offset);
  both.clip.insert(both.clip.end(), layers[1].clip.begin(), layers[1].clip.end());
  both.color.insert(both.color.end(), layers[1].color.begin(), layers[1].color.end());
  RenderState painter = no_depth_no_cull();
  painter.order = DrawOrder::back_to_front;
  const auto draw = [&](int samples, int threads, bool together, bool separate_frames) {
    Framebuffer fb(width, height, samples);
    Renderer renderer(threads);
    renderer.clear(fb, glm::vec4(0.1f, 0.1f, 0.15f, 1.0f));
    const std::vector<ColorShader::Vertex> a = color_vertices(layers[0]), b = color_vertices(layers[1]),
                                           ab = color_vertices(both);
    if (together) {
      renderer.draw(fb, ColorShader{}, std::span<const ColorShader::Vertex>(ab), both.indices, painter);
    } else {
      renderer.draw(fb, ColorShader{}, std::span<const ColorShader::Vertex>(a), layers[0].indices, painter);
      if (separate_frames) renderer.finish(fb);
      renderer.draw(fb, ColorShader{}, std::span<const ColorShader::Vertex>(b), layers[1].indices, painter);
    }
    renderer.finish(fb);
    return fb;
  };
  for (const int samples : {1, 4}) {
    const Framebuffer whole = draw(samples, 1, true, false);
    EXPECT_FALSE(std::ranges::equal(draw(samples, 1, false, true).color(), whole.color()))  // the layers interleave
        << samples << " samples";
    for (const int threads : {1, 2, 3})
      EXPECT_TRUE(std::ranges::equal(draw(samples, threads, false, false).color(), whole.color()))
          << samples << " samples, " << threads << " threads";
  }
}

TEST(FastPath, OutOfRangeIndicesSkipTheirTriangle) {
  ClipMesh m = jittered_grid(2, 2, 1, false);
  const std::size_t good = m.indices.size() / 3;
  m.indices.insert(m.indices.end(), {0u, 1u, 999u});
  Renderer renderer(2);
  Framebuffer fb(16, 16);
  const std::vector<ColorShader::Vertex> vertices = color_vertices(m);
  renderer.draw(fb, ColorShader{}, std::span<const ColorShader::Vertex>(vertices), m.indices, no_depth_no_cull());
  EXPECT_EQ(renderer.last_stats().invalid, 1u);
  EXPECT_EQ(renderer.last_stats().primitives, good + 1);
}

}  // namespace
}  // namespace facet::test
