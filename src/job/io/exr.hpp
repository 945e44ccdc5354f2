// exr.hpp - encoding float images as OpenEXR files in memory.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

namespace facet {

// An OpenEXR file of width x height pixels with `channels` (1: Y; 2: R G; 3: R G B) 32-bit float channels, ZIP-compressed,
// from values laid out pixel by pixel, top row first. Throws std::runtime_error when OpenEXR fails.
std::vector<std::uint8_t> encode_exr(int width, int height, int channels, std::span<const float> values);

// How many pixels one byte of an OpenEXR file may describe before its header is taken to lie: ZIP and RLE can pack
// a constant image very tightly, so the bound is loose; it still keeps a small file from claiming gigapixels.
inline constexpr std::uint64_t kMaxExrTexelsPerByte = 4096;

// Decodes an OpenEXR image (scanline or tiled, any compression the library reads, half, float or uint channels)
// held in memory into linear RGB floats, pixel by pixel, top row first, over its data window. R, G and B are read
// by name (any layer prefix ignored: the first layer's, or the unnamed one); a file with only Y (luminance) gives
// grey; a missing channel reads as 0. `check_size(width, height)` is called with the data window's size before
// anything is allocated and may throw. Throws InputError(source, problem) for a file OpenEXR cannot read, with the
// library's message, or one whose data window is empty or absurd.
std::vector<float> decode_exr_rgb(const void* data, std::size_t size, const std::string& source,
                                  const std::function<void(int, int)>& check_size, int& width, int& height);

}  // namespace facet
