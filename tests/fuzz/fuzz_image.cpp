// fuzz_image.cpp - libFuzzer target for the texture decoder (stb_image's PNG, JPEG, TGA and BMP, then mipmaps).
#include <cstddef>
#include <cstdint>
#include <span>

#include "fuzz_input.hpp"
#include "scene/texture/decode.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return facet::fuzz::run(
      [&] { (void)facet::decode_texture_file(std::span(data, size), facet::TexelEncoding::srgb, "input"); });
}
