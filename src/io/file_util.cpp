// file_util.cpp - whole-file reading for the image decoders (PNG reader and texture loader).
#include "io/file_util.hpp"

#include <cctype>
#include <cerrno>
#include <climits>
#include <cstdio>
#include <memory>
#include <system_error>

#include "facet/error.hpp"

namespace facet {
namespace {

[[noreturn]] void fail(const std::filesystem::path& path, const std::string& problem) {
  throw InputError(path.string(), problem);
}

}  // namespace

std::string errno_text(int err) { return std::generic_category().message(err); }

std::string lower_extension(const std::filesystem::path& path) {
  std::string extension = path.extension().string();
  for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return extension;
}

std::vector<unsigned char> read_image_file(const std::filesystem::path& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) fail(path, "is a directory, not an image file");
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "rb"), &std::fclose);
  if (!file) fail(path, "cannot open: " + errno_text(errno));
  std::vector<unsigned char> bytes;
  unsigned char chunk[1 << 16];
  for (;;) {
    const std::size_t n = std::fread(chunk, 1, sizeof chunk, file.get());
    bytes.insert(bytes.end(), chunk, chunk + n);
    // stb_image takes the length as an int.
    if (bytes.size() > static_cast<std::size_t>(INT_MAX)) fail(path, "file is too large for an image (over 2 GiB)");
    if (n < sizeof chunk) break;
  }
  if (std::ferror(file.get())) fail(path, "cannot read: " + errno_text(errno));
  if (bytes.empty()) fail(path, "file is empty");
  return bytes;
}

}  // namespace facet
