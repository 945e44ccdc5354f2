// text.cpp - text and rectangles blended into RGBA8 images; the glyphs are stb_easy_font's quads.
#include "facet/text.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#include <stb_easy_font.h>
#pragma GCC diagnostic pop

namespace facet {

namespace {

// stb_easy_font takes a mutable C string of printable ASCII.
std::string printable_ascii(std::string_view text) {
  std::string s(text);
  for (char& c : s)
    if (c != '\n' && (c < 32 || c > 126)) c = ' ';
  return s;
}

// One vertex of stb_easy_font's output: x, y, z and a colour, 16 bytes.
struct FontVertex {
  float x, y, z;
  unsigned char color[4];
};

}  // namespace

TextSize text_size(std::string_view text, int scale) {
  std::string s = printable_ascii(text);
  return {stb_easy_font_width(s.data()) * scale, stb_easy_font_height(s.data()) * scale};
}

void fill_rect(std::span<std::uint8_t> rgba, int width, int height, int x, int y, int w, int h, glm::vec4 color) {
  const int x0 = std::max(x, 0), y0 = std::max(y, 0);
  const int x1 = std::min(x + w, width), y1 = std::min(y + h, height);
  const float a = std::clamp(color.a, 0.0f, 1.0f);
  std::uint8_t src[3];
  for (int c = 0; c < 3; ++c) src[c] = static_cast<std::uint8_t>(std::lround(std::clamp(color[c], 0.0f, 1.0f) * 255));
  for (int py = y0; py < y1; ++py)
    for (int px = x0; px < x1; ++px) {
      std::uint8_t* p = &rgba[(static_cast<std::size_t>(py) * width + px) * 4];
      for (int c = 0; c < 3; ++c) p[c] = static_cast<std::uint8_t>(std::lround(src[c] * a + p[c] * (1.0f - a)));
      p[3] = static_cast<std::uint8_t>(std::lround(255.0f * a + p[3] * (1.0f - a)));
    }
}

void draw_text(std::span<std::uint8_t> rgba, int width, int height, int x, int y, std::string_view text,
               glm::vec4 color, int scale) {
  std::string s = printable_ascii(text);
  // At most 4 vertices of 16 bytes for each of a glyph's few dozen quads; 270 bytes per character is the
  // library's own estimate.
  std::vector<FontVertex> vertices(s.size() * 300 / sizeof(FontVertex) + 4);
  unsigned char white[4] = {255, 255, 255, 255};
  const int quads = stb_easy_font_print(0.0f, 0.0f, s.data(), white, vertices.data(),
                                        static_cast<int>(vertices.size() * sizeof(FontVertex)));
  for (int q = 0; q < quads; ++q) {
    const FontVertex& a = vertices[static_cast<std::size_t>(4 * q)];
    const FontVertex& c = vertices[static_cast<std::size_t>(4 * q + 2)];
    const int qx = static_cast<int>(a.x) * scale, qy = static_cast<int>(a.y) * scale;
    fill_rect(rgba, width, height, x + qx, y + qy, static_cast<int>(c.x - a.x) * scale,
              static_cast<int>(c.y - a.y) * scale, color);
  }
}

}  // namespace facet
