// test_hidden_surfaces.cpp - the depth buffer resolves what no painter's order can; draw order cannot change it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <glm/gtc/matrix_transform.hpp>
#include <random>

#include "facet/detail/raster.hpp"
#include "support/draw_helpers.hpp"

namespace facet::test {
namespace {

// Two triangles that pierce each other (the case "Computer Graphics from Scratch" gives of no valid painter's
// order): red leans away to the right, green leans away to the left, so each is in front of the other on one side.
ClipMesh interpenetrating(const glm::mat4& clip_from_world) {
  ClipMesh m;
  const glm::vec3 red[3] = {{-1.0f, -0.8f, -2.0f}, {1.0f, -0.8f, -4.0f}, {0.0f, 0.9f, -3.0f}};
  const glm::vec3 green[3] = {{-1.0f, 0.8f, -4.0f}, {0.0f, -0.9f, -3.0f}, {1.0f, 0.8f, -2.0f}};
  for (const glm::vec3& p : red) {
    m.clip.push_back(clip_from_world * glm::vec4(p, 1));
    m.color.emplace_back(1, 0, 0);
  }
  for (const glm::vec3& p : green) {
    m.clip.push_back(clip_from_world * glm::vec4(p, 1));
    m.color.emplace_back(0, 1, 0);
  }
  m.indices = {0, 1, 2, 3, 4, 5};
  return m;
}

ClipMesh only(const ClipMesh& m, std::size_t triangle) {
  ClipMesh one = m;
  one.indices.assign(m.indices.begin() + 3 * triangle, m.indices.begin() + 3 * triangle + 3);
  return one;
}

TEST(HiddenSurfaces, DepthBufferResolvesInterpenetratingTriangles) {
  const int size = 96;
  const ClipMesh scene = interpenetrating(glm::perspective(glm::radians(50.0f), 1.0f, 0.5f, 10.0f));
  RenderState depth;
  depth.cull = CullMode::none;
  // Ground truth per pixel: the nearer of the two triangles, each drawn alone with its own depth.
  const Framebuffer red = render_colors(only(scene, 0), size, size, depth, 1);
  const Framebuffer green = render_colors(only(scene, 1), size, size, depth, 1);
  const Framebuffer both = render_colors(scene, size, size, depth, 2);
  int red_front = 0, green_front = 0;
  for (std::size_t i = 0; i < both.color().size(); ++i) {
    const std::uint32_t expected = red.depth()[i] < green.depth()[i] ? red.color()[i] : green.color()[i];
    ASSERT_EQ(both.color()[i], expected) << "pixel " << i;
    if (red.depth()[i] < 1 && green.depth()[i] < 1) (red.depth()[i] < green.depth()[i] ? red_front : green_front)++;
  }
  ASSERT_GT(red_front, 50);
  ASSERT_GT(green_front, 50);

  // Without a depth buffer, either draw order is wrong somewhere: there is no valid painter's order.
  RenderState painter = no_depth_no_cull();
  for (const bool swap : {false, true}) {
    ClipMesh ordered = scene;
    if (swap) ordered.indices = {3, 4, 5, 0, 1, 2};
    const Framebuffer flat = render_colors(ordered, size, size, painter, 1);
    EXPECT_FALSE(std::equal(flat.color().begin(), flat.color().end(), both.color().begin()));
  }
  // The painter's algorithm mode sorts by depth, and still cannot get both right.
  painter.order = DrawOrder::back_to_front;
  const Framebuffer sorted = render_colors(scene, size, size, painter, 1);
  EXPECT_FALSE(std::equal(sorted.color().begin(), sorted.color().end(), both.color().begin()));
}

TEST(HiddenSurfaces, ShufflingTrianglesDoesNotChangeADepthBufferedImage) {
  const glm::mat4 clip_from_world = glm::perspective(glm::radians(45.0f), 1.5f, 0.1f, 10.0f) *
                                    glm::lookAt(glm::vec3(1.2f, 0.8f, 2.4f), glm::vec3(0), glm::vec3(0, 1, 0));
  ClipMesh scene = closed_sphere(19, 31, clip_from_world);
  RenderState depth;
  depth.cull = CullMode::none;
  const Framebuffer reference = render_colors(scene, 240, 160, depth, 2);
  std::mt19937 rng(42);
  for (int round = 0; round < 3; ++round) {
    std::vector<std::array<std::uint32_t, 3>> triangles;
    for (std::size_t t = 0; t < scene.indices.size(); t += 3)
      triangles.push_back({scene.indices[t], scene.indices[t + 1], scene.indices[t + 2]});
    std::shuffle(triangles.begin(), triangles.end(), rng);
    scene.indices.clear();
    for (const auto& t : triangles) scene.indices.insert(scene.indices.end(), t.begin(), t.end());
    const Framebuffer shuffled = render_colors(scene, 240, 160, depth, 2);
    EXPECT_TRUE(std::equal(reference.color().begin(), reference.color().end(), shuffled.color().begin()));
  }
}

TEST(HiddenSurfaces, PainterSortsBackToFrontWithoutDepthBuffer) {
  // Two parallel quads drawn near-first: as given, the far one paints over; sorted, the near one wins.
  const glm::mat4 proj = glm::perspective(glm::radians(60.0f), 1.0f, 0.1f, 10.0f);
  ClipMesh m;
  for (const float z : {-2.0f, -4.0f})
    for (const glm::vec2 c : {glm::vec2(-3, -3), glm::vec2(3, -3), glm::vec2(3, 3), glm::vec2(-3, 3)}) {
      m.clip.push_back(proj * glm::vec4(c, z, 1));
      m.color.push_back(z > -3 ? glm::vec3(1, 0, 0) : glm::vec3(0, 0, 1));
    }
  m.indices = {0, 1, 2, 0, 2, 3, 4, 5, 6, 4, 6, 7};
  RenderState state = no_depth_no_cull();
  EXPECT_EQ(render_colors(m, 32, 32, state, 1).pixel(16, 16) & 0xffffff, 0xff0000u);  // blue on top
  state.order = DrawOrder::back_to_front;
  EXPECT_EQ(render_colors(m, 32, 32, state, 1).pixel(16, 16) & 0xffffff, 0x0000ffu);  // red on top
}

}  // namespace
}  // namespace facet::test

namespace facet::test {
namespace {

// Stacked screen-filling quads drawn nearest first let hierarchical depth reject whole blocks; a following draw
// under GREATER raises stored depth, which the block bounds must follow. The reference rasterizer has no
// hierarchical depth, so any wrong rejection shows up as a difference.
TEST(HiddenSurfaces, HierarchicalDepthRejectsOnlyHiddenBlocks) {
  const glm::mat4 proj = glm::perspective(glm::radians(60.0f), 1.5f, 0.1f, 10.0f);
  ClipMesh quads;
  for (int i = 0; i < 6; ++i) {
    const float z = -1.5f - 0.4f * i, s = 2.0f + 0.5f * i, shift = 0.15f * i;
    for (const glm::vec2 c : {glm::vec2(-1, -1), glm::vec2(1, -1), glm::vec2(1, 1), glm::vec2(-1, 1)}) {
      quads.clip.push_back(proj * glm::vec4(c * s + glm::vec2(shift, -shift), z, 1));
      quads.color.emplace_back(0.15f * i, 1.0f - 0.15f * i, 0.5f);
    }
    const auto b = static_cast<std::uint32_t>(4 * i);
    quads.indices.insert(quads.indices.end(), {b, b + 1, b + 2, b, b + 2, b + 3});
  }
  ClipMesh tilted = closed_sphere(12, 18, proj * glm::translate(glm::mat4(1), glm::vec3(0.3f, 0, -2.6f)));
  RenderState greater;
  greater.depth_func = DepthFunc::greater;
  greater.cull = CullMode::none;
  const std::vector<ColorShader::Vertex> quad_vertices = color_vertices(quads), ball = color_vertices(tilted);
  ClipMesh behind = quads;  // every quad but the nearest
  behind.indices.erase(behind.indices.begin(), behind.indices.begin() + 6);
  auto draw_all = [&](Framebuffer& fb, bool reference_path) {
    Renderer renderer(2);
    if (reference_path) reference::clear(fb, glm::vec4(0, 0, 0, 1));
    else renderer.clear(fb, glm::vec4(0, 0, 0, 1));
    auto draw = [&](const std::vector<ColorShader::Vertex>& v, const ClipMesh& m, const RenderState& s) {
      if (reference_path) reference::draw(fb, ColorShader{}, std::span<const ColorShader::Vertex>(v), m.indices, s);
      else renderer.draw(fb, ColorShader{}, std::span<const ColorShader::Vertex>(v), m.indices, s);
    };
    draw(quad_vertices, quads, RenderState{});
    draw(ball, tilted, greater);
    draw(quad_vertices, behind, RenderState{});  // visible only where the sphere raised the stored depth
    renderer.finish(fb);
  };
  Framebuffer fast(160, 112), slow(160, 112);
  draw_all(fast, false);
  draw_all(slow, true);
  // Colours may differ by one level of rounding (plane versus barycentric evaluation); more means a wrong surface.
  std::size_t different = 0;
  for (std::size_t i = 0; i < fast.color().size(); ++i)
    for (int c = 0; c < 3; ++c)
      if (std::abs(int((fast.color()[i] >> (8 * c)) & 0xff) - int((slow.color()[i] >> (8 * c)) & 0xff)) > 1) {
        ++different;
        break;
      }
  EXPECT_LE(different, fast.color().size() / 1000);
}

// Hierarchical depth bounds each block by the plane's extremes at the corners of the block's rectangle; the block
// walk picks the two corners by the gradient's signs. They must be exactly the least and greatest of all four
// corner values, whatever the plane (any signs, zero gradients, large and tiny magnitudes) and offset.
TEST(BlockDepthRange, IsTheLeastAndGreatestCornerValue) {
  std::mt19937 rng(17);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  for (int trial = 0; trial < 20000; ++trial) {
    detail::TriangleSetup tri{};
    const float scale = std::ldexp(1.0f, static_cast<int>(rng() % 30) - 24);
    tri.depth = {0.5f + 0.5f * unit(rng), trial % 7 == 0 ? 0.0f : unit(rng) * scale,
                 trial % 5 == 0 ? -0.0f : unit(rng) * scale};
    tri.origin_x = 1000.0f * (unit(rng) + 1.0f), tri.origin_y = 600.0f * (unit(rng) + 1.0f);
    const int x0 = static_cast<int>(rng() % 1900), y0 = static_cast<int>(rng() % 1060);
    const int x1 = x0 + static_cast<int>(rng() % 8), y1 = y0 + static_cast<int>(rng() % 8);
    const float offset = trial % 3 == 0 ? 0.0f : 1e-3f * unit(rng);
    float z[4];
    int n = 0;
    for (int y : {y0, y1})
      for (int x : {x0, x1})
        z[n++] = detail::evaluate(tri.depth, static_cast<float>(x) + 0.5f - tri.origin_x,
                                  static_cast<float>(y) + 0.5f - tri.origin_y);
    const detail::DepthRange range = detail::raster_block_depth_range(tri, offset, x0, y0, x1, y1);
    ASSERT_EQ(range.nearest, std::clamp(*std::min_element(z, z + 4) + offset, 0.0f, 1.0f)) << "trial " << trial;
    ASSERT_EQ(range.farthest, std::clamp(*std::max_element(z, z + 4) + offset, 0.0f, 1.0f)) << "trial " << trial;
  }
}

}  // namespace
}  // namespace facet::test
