// text.hpp - labels and overlays drawn into RGBA8 images with a small built-in bitmap font (stb_easy_font).
#pragma once

#include <cstdint>
#include <span>
#include <string_view>

#include <glm/glm.hpp>

namespace facet {

struct TextSize {
  int width = 0, height = 0;
};

// The pixels `text` covers when drawn at `scale` (font dots per pixel side): the longest line's width and the
// height of all its lines. Printable ASCII only; other bytes take a space's width.
TextSize text_size(std::string_view text, int scale = 1);

// Draws text with its top-left corner at (x, y) into rgba (width * height RGBA bytes, top row first), each font
// dot a scale x scale square of `color` blended over the image by its alpha; '\n' starts a new line. What falls
// outside the image is clipped.
void draw_text(std::span<std::uint8_t> rgba, int width, int height, int x, int y, std::string_view text,
               glm::vec4 color, int scale = 1);

// Blends color over the rectangle [x, x + w) x [y, y + h) of rgba, clipped to the image.
void fill_rect(std::span<std::uint8_t> rgba, int width, int height, int x, int y, int w, int h, glm::vec4 color);

}  // namespace facet
