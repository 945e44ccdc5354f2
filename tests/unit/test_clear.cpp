// test_clear.cpp - deferred clears reach every pixel: whole tile rows, runs of tiles beside drawn ones, cut tiles.
#include <gtest/gtest.h>

#include <cstdint>
#include <span>
#include <vector>

#include "support/draw_helpers.hpp"

namespace facet::test {
namespace {

// A right triangle with legs of `size` pixels, `offset` pixels into the 64x64 tile (tile_x, tile_y) of a
// width x height target, in clip space.
void add_triangle_in_tile(ClipMesh& m, int tile_x, int tile_y, int width, int height, float offset = 10.0f,
                          float size = 20.0f) {
  const auto clip = [&](float px, float py) {
    return glm::vec4(2.0f * px / static_cast<float>(width) - 1.0f, 1.0f - 2.0f * py / static_cast<float>(height), 0.0f, 1.0f);
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
  add_triangle_in_tile(m, 0, 2, width, height);  // row 2: one run [1, 4]
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

}  // namespace
}  // namespace facet::test
