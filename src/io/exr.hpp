// exr.hpp - encoding float images as OpenEXR files in memory.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace facet {

// An OpenEXR file of width x height pixels with `channels` (1: Y; 3: R G B) 32-bit float channels, ZIP-compressed,
// from values laid out pixel by pixel, top row first. Throws std::runtime_error when OpenEXR fails.
std::vector<std::uint8_t> encode_exr(int width, int height, int channels, std::span<const float> values);

}  // namespace facet
