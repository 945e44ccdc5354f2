// png.hpp - encoding 8-bit images as PNG files in memory, with libdeflate.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace facet {

// A PNG of width x height pixels with `channels` 8-bit samples each (1 grey, 3 RGB, 4 RGBA), from pixels laid out
// row by row, top row first. Every row takes the Up filter (the difference from the row above), which suits
// rendered images (flat backgrounds, smooth shading) and costs one subtraction per byte; libdeflate compresses the
// rows at level 2 (on a rendered 1920x1080 frame, level 6 saves a tenth of the file for half again the time). Throws
// std::invalid_argument for a bad size or channel count, std::runtime_error if compression fails. The pixels may
// hold more samples each than the file (source_channels, e.g. RGBA pixels written as RGB): the extra ones, last in
// each pixel, are dropped as the rows are filtered, without a copy of the image.
std::vector<std::uint8_t> encode_png(int width, int height, int channels, std::span<const std::uint8_t> pixels,
                                     int source_channels = 0);

}  // namespace facet
