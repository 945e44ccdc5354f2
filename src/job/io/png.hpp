// png.hpp - encoding 8-bit images as PNG files in memory, with zlib.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "facet/image_io.hpp"

namespace facet {

// A PNG of width x height pixels with `channels` 8-bit samples each (1 grey, 3 RGB, 4 RGBA), from pixels laid out
// row by row, top row first. Every row takes the Up filter (the difference from the row above), which suits
// rendered images (flat backgrounds, smooth shading) and costs one subtraction per byte; zlib compresses the rows
// with run-length matches, in bands of at least 1 MiB of rows, up to `threads` of them at once (the calling thread
// and threads - 1 started for the call), into one stream. The rows are filtered a few at a time, as they are
// compressed: the encoder holds no copy of the image. Throws std::invalid_argument for a bad size or channel count,
// std::runtime_error if compression fails. The pixels may hold more samples each than the file (source_channels,
// e.g. RGBA pixels written as RGB): the extra ones, last in each pixel, are dropped as the rows are filtered. Each
// of `text` is a tEXt chunk before the image data; std::invalid_argument for a keyword or text PNG forbids.
std::vector<std::uint8_t> encode_png(int width, int height, int channels, std::span<const std::uint8_t> pixels,
                                     int source_channels = 0, int threads = 1, std::span<const PngText> text = {});

}  // namespace facet
