// image_decode.hpp - image files to RGBA bytes: PNG with libspng, JPEG with libjpeg-turbo, TGA and BMP with stb_image.
#pragma once

#include <cstdint>
#include <optional>
#include <utility>
#include <span>
#include <string>
#include <vector>

namespace facet {

struct DecodedImage {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgba;  // width * height * 4 bytes, top row first
};

// Decodes an image file's bytes, chosen by its signature. PNG and JPEG, the formats models use, go through
// libraries made for untrusted input (stb_image, fuzzed, read past its buffers on malformed PNG and JPEG files);
// TGA and BMP through stb_image. An image wider or taller than max_size is refused from its header, before any
// pixel is decoded. Throws InputError(source, problem).
DecodedImage decode_image(std::span<const unsigned char> bytes, int max_size, const std::string& source);

// The width and height an image file's header states, read by the same decoders without decoding pixels; nullopt
// when the header cannot be read (decode_image then says why).
std::optional<std::pair<int, int>> image_size(std::span<const unsigned char> bytes);

}  // namespace facet
