// file_util.hpp - whole-file reading for the image decoders, with the system's reason when it fails.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace facet {

// The system's message for an errno value, e.g. "No such file or directory".
std::string errno_text(int err);

// The extension of path in lower case, with its dot (".obj"), or "" for none.
std::string lower_extension(const std::filesystem::path& path);

// Reads the whole of an image file into memory for stb_image, whose own fopen only says "can't fopen". Throws
// InputError when path is a directory, cannot be opened or read, is empty, or is too large for stb_image's int sizes.
std::vector<unsigned char> read_image_file(const std::filesystem::path& path);

}  // namespace facet
