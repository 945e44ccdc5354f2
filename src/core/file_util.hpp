// file_util.hpp - whole-file reading of regular files, with the system's reason when it fails.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "facet/framebuffer.hpp"

namespace facet {

// A whole file's bytes. Large files land on huge pages (CacheAlignedAllocator): a 28 MB model read into ordinary
// memory takes 7,000 page faults, about 90 ms on the development machine, against 14 on 2 MiB pages.
using FileBytes = std::basic_string<char, std::char_traits<char>, CacheAlignedAllocator<char>>;

// The system's message for an errno value, e.g. "No such file or directory".
std::string errno_text(int err);

// The extension of path in lower case, with its dot (".obj"), or "" for none.
std::string lower_extension(const std::filesystem::path& path);

// Reads the whole of a regular file, at most max_bytes long. Throws InputError(source, problem) when it does not
// exist, cannot be opened or read, is empty or too large, or is not a regular file: a device (/dev/zero), a FIFO
// (opened without waiting for a writer) or a directory is never read, so a model cannot make facet read forever.
FileBytes read_regular_file(const std::filesystem::path& path, std::uintmax_t max_bytes, const std::string& source);

// The same for an image file handed to stb_image (at most 2 GiB: stb_image takes sizes as int), named by its path.
std::vector<unsigned char> read_image_file(const std::filesystem::path& path);

}  // namespace facet
