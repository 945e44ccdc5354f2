// decode.hpp - an image file's bytes decoded into a Texture, for load_texture and the image fuzzer.
#pragma once

#include <filesystem>
#include <span>

#include "facet/texture.hpp"

namespace facet {

// What load_texture does once it has read the file: the bytes of a PNG, JPEG, TGA or BMP image (at most 2 GiB)
// decoded, flipped so that row 0 is v = 0, with mipmaps. Throws InputError(path, problem) as load_texture does.
Texture decode_texture_file(std::span<const unsigned char> bytes, TexelEncoding encoding,
                            const std::filesystem::path& path);

}  // namespace facet
