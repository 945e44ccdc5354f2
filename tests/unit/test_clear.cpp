// test_clear.cpp - deferred clears reach every pixel: whole tile rows, runs of tiles beside drawn ones, cut tiles.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "support/draw_helpers.hpp"

namespace facet::test::clear_tests {
namespace {

// A right triangle with legs of `size` pixels, `offset` pixels into the 64x64 tile (tile_x, tile_y) of a
// width x height target, in clip space.
void add_triangle_in_tile(ClipMesh& m, int tile_x, int tile_y, int width, int height, float offset = 10.0f,
                          float size = 20.0f) {
  const auto clip = [&](float px, float py) {
    return glm::vec4(2.0f * px / static_cast<float>(width) - 1.0f, 1.0f - 2.0f * py / static_cast<float>(height), 0.0f,
                     1.0f);
  };
  const float x = static_cast<float>(tile_x * kTileSize) + offset, y = static_cast<float>(tile_y * kTileSize) + offset;
  const auto first = static_cast<std::uint32_t>(m.clip.size());
  m.clip.insert(m.clip.end(), {clip(x, y), clip(x, y + size), clip(x + size, y)});
  m.color.insert(m.color.end(), 3, glm::vec3(1.0f, 0.0f, 0.0f));
  m.indices.insert(m.indices.end(), {first, first + 1, first + 2});
}

// After a first clear, a second one with triangles in some tiles: no pixel may keep the first clear's colour or
// depth, whichever way its tile was cleared (by its own draw, in a run of tiles, or with its whole row).
TEST(Clear, EveryPixelReceivesTheNewClear) {
  const int width = 300, height = 200;  // 5 x 4 tiles, the last column 44 pixels wide, the last row 8 tall
  ClipMesh m;
  add_triangle_in_tile(m, 1, 1, width, height);  // row 1: runs [0], [2], [4]
  add_triangle_in_tile(m, 3, 1, width, height);
  add_triangle_in_tile(m, 0, 2, width, height);              // row 2: one run [1, 4]
  add_triangle_in_tile(m, 4, 3, width, height, 1.0f, 6.0f);  // row 3 (8 pixels tall): one run [0, 3]
  const std::vector<ColorShader::Vertex> vertices = color_vertices(m);
  for (const bool deferred : {true, false}) {
    Framebuffer fb(width, height);
    Renderer renderer(2);
    renderer.clear(fb, glm::vec4(0.0f, 1.0f, 0.0f, 1.0f), 0.25f);
    renderer.finish(fb);
    renderer.clear(fb, glm::vec4(0.0f, 0.0f, 1.0f, 1.0f), 0.75f);
    RenderState state = no_depth_no_cull();
    state.defer_shading = deferred;
    renderer.draw(fb, ColorShader{}, std::span<const ColorShader::Vertex>(vertices), m.indices, state);
    renderer.finish(fb);
    const std::uint32_t old_color = pack_rgba8(glm::vec4(0.0f, 1.0f, 0.0f, 1.0f));
    const std::uint32_t new_color = pack_rgba8(glm::vec4(0.0f, 0.0f, 1.0f, 1.0f));
    int drawn = 0;
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) {
        const std::size_t i = static_cast<std::size_t>(y) * width + x;
        ASSERT_NE(fb.color()[i], old_color) << "pixel " << x << ", " << y << (deferred ? " (deferred)" : "");
        ASSERT_NE(fb.depth()[i], 0.25f) << "pixel " << x << ", " << y << (deferred ? " (deferred)" : "");
        drawn += fb.color()[i] != new_color;
      }
    // Three triangles of about 200 pixels and one of about 18.
    EXPECT_GT(drawn, 3 * 180 + 10) << "the four triangles were drawn";
    EXPECT_LT(drawn, 3 * 220 + 30);
  }
}

// Frame after frame with the same clear, as an animation renders: tiles that still hold the clear are skipped, so
// each frame must equal the same frame drawn on a fresh target, whatever earlier frames or the caller wrote.
TEST(Clear, RepeatedClearsMatchAFreshTarget) {
  const int width = 300, height = 200;
  ClipMesh first, second;
  add_triangle_in_tile(first, 1, 1, width, height);
  add_triangle_in_tile(second, 3, 2, width, height);
  const std::vector<ColorShader::Vertex> first_vertices = color_vertices(first),
                                         second_vertices = color_vertices(second);
  const glm::vec4 blue(0.0f, 0.0f, 1.0f, 1.0f);
  for (const bool deferred : {true, false}) {
    RenderState state = no_depth_no_cull();
    state.depth_test = true;
    state.defer_shading = deferred;
    const auto frame = [&](Framebuffer& fb, Renderer& renderer, const ClipMesh* m,
                           const std::vector<ColorShader::Vertex>* vertices) {
      renderer.clear(fb, blue, 0.75f);
      if (m) renderer.draw(fb, ColorShader{}, std::span<const ColorShader::Vertex>(*vertices), m->indices, state);
      renderer.finish(fb);
    };
    const auto same = [](const Framebuffer& a, const Framebuffer& b) {
      return std::equal(a.color().begin(), a.color().end(), b.color().begin()) &&
             std::equal(a.depth().begin(), a.depth().end(), b.depth().begin());
    };
    Renderer renderer(2);
    Framebuffer fb(width, height), fresh_second(width, height), fresh_empty(width, height);
    frame(fresh_second, renderer, &second, &second_vertices);
    frame(fresh_empty, renderer, nullptr, nullptr);

    frame(fb, renderer, &first, &first_vertices);
    frame(fb, renderer, &second, &second_vertices);  // the first frame's triangle must be cleared away
    EXPECT_TRUE(same(std::as_const(fb), fresh_second)) << (deferred ? "deferred" : "immediate");

    // A write through color(), then one through depth(), into tiles no draw touches, each before an empty frame.
    fb.mutable_color()[5] = 0x12345678u;
    frame(fb, renderer, nullptr, nullptr);
    EXPECT_TRUE(same(std::as_const(fb), fresh_empty)) << (deferred ? "deferred" : "immediate");
    fb.mutable_depth()[static_cast<std::size_t>(150) * width + 40] = 0.125f;
    frame(fb, renderer, nullptr, nullptr);
    EXPECT_TRUE(same(std::as_const(fb), fresh_empty)) << (deferred ? "deferred" : "immediate");

    // A different clear reaches tiles that held the previous one.
    renderer.clear(fb, glm::vec4(1.0f, 0.0f, 0.0f, 1.0f), 0.5f);
    renderer.finish(fb);
    const Framebuffer& view = fb;
    EXPECT_TRUE(std::all_of(view.color().begin(), view.color().end(),
                            [](std::uint32_t c) { return c == pack_rgba8(glm::vec4(1.0f, 0.0f, 0.0f, 1.0f)); }));
    EXPECT_TRUE(std::all_of(view.depth().begin(), view.depth().end(), [](float z) { return z == 0.5f; }));
  }
}

// A framebuffer that does not keep its depth draws the same colours, whether its frame is one tile pass or several
// parts (which keep the depth between them), at 1 and 4 samples; after finish() its depth is discarded: reading it
// throws, and the next frame, drawn without a clear, starts from depth 1 (a far quad shows everywhere).
TEST(Clear, DiscardedDepthKeepsTheImageAndStartsTheNextFrameFar) {
  const int width = 300, height = 200;
  ClipMesh near_triangles = triangle_soup(300, 7);
  ClipMesh far_quad;
  for (const glm::vec2 c : {glm::vec2(-1, -1), glm::vec2(1, -1), glm::vec2(1, 1), glm::vec2(-1, 1)}) {
    far_quad.clip.emplace_back(c, 0.98f, 1.0f);
    far_quad.color.emplace_back(0.0f, 1.0f, 0.0f);
  }
  far_quad.indices = {0, 1, 2, 0, 2, 3};
  const std::vector<ColorShader::Vertex> near_vertices = color_vertices(near_triangles),
                                         far_vertices = color_vertices(far_quad);
  RenderState state;
  state.cull = CullMode::none;
  for (const int samples : {1, 4})
    for (const std::size_t limit : {Renderer::kDefaultRecordedBytes, std::size_t{0}}) {
      const auto draw = [&](bool keep) {
        Framebuffer fb(width, height, samples);
        fb.keep_depth(keep);
        Renderer renderer(2);
        renderer.set_recorded_bytes_limit(limit);
        renderer.clear(fb, glm::vec4(0.1f, 0.1f, 0.15f, 1.0f));
        const std::span<const std::uint32_t> indices(near_triangles.indices);
        for (std::size_t first = 0; first < indices.size(); first += 150)  // several draws: parts at limit 0
          renderer.draw(fb, ColorShader{}, std::span<const ColorShader::Vertex>(near_vertices),
                        indices.subspan(first, 150), state);
        renderer.finish(fb);
        std::vector<std::uint32_t> image(fb.color().begin(), fb.color().end());
        renderer.draw(fb, ColorShader{}, std::span<const ColorShader::Vertex>(far_vertices), far_quad.indices, state);
        renderer.finish(fb);
        return std::pair{std::move(image), std::move(fb)};
      };
      const auto [kept_image, kept] = draw(true);
      const auto [image, discarded] = draw(false);
      EXPECT_EQ(image, kept_image) << samples << " samples, limit " << limit;
      EXPECT_THROW((void)discarded.depth(), std::logic_error);
      EXPECT_THROW((void)discarded.depth_at(0, 0), std::logic_error);
      const std::uint32_t green = pack_rgba8(glm::vec4(0.0f, 1.0f, 0.0f, 1.0f));
      EXPECT_TRUE(std::ranges::all_of(discarded.color(), [&](std::uint32_t c) { return c == green; }));
      EXPECT_FALSE(std::ranges::all_of(kept.color(), [&](std::uint32_t c) { return c == green; }));
    }
  Framebuffer fb(width, height);
  fb.keep_depth(false);
  Renderer renderer(2);
  renderer.clear(fb, glm::vec4(0.0f), 0.25f);
  renderer.draw(fb, ColorShader{}, std::span<const ColorShader::Vertex>(near_vertices), near_triangles.indices, state);
  renderer.finish(fb);
  const std::span<const float> depth = fb.mutable_depth();  // writable access settles the discarded depth
  EXPECT_TRUE(std::ranges::all_of(depth, [](float z) { return z == 1.0f; }));
}

}  // namespace
}  // namespace facet::test::clear_tests
