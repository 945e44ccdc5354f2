// model_io.cpp - load_model(): checks and reads a model file once, then hands it to the OBJ, PLY or STL reader.
#include "facet/model_io.hpp"

#include <cctype>
#include <fstream>
#include <iostream>
#include <new>
#include <string>

#include "facet/error.hpp"
#include "io/loaders.hpp"

namespace facet {

namespace fs = std::filesystem;

std::string printable(std::string_view s) {
  std::string out(s.substr(0, 200));
  for (char& c : out)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
  return out;
}

void warn(const std::string& source, const std::string& message) {
  std::cerr << "facet: warning: " << source << ": " << message << '\n';
}

namespace {

enum class Format { kObj, kPly, kStl, kUnknown };

constexpr const char* kSupported = "supported: .obj, .ply, .stl";

// Problems every format shares, checked before the format so a mistyped path says "no such file".
std::uintmax_t checked_file_size(const fs::path& path, const std::string& source) {
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (!fs::exists(status)) throw InputError(source, "no such file");
  if (!fs::is_regular_file(status)) throw InputError(source, "not a regular file");
  const std::uintmax_t size = fs::file_size(path, ec);
  if (ec) throw InputError(source, "cannot read file size (" + ec.message() + ")");
  if (size == 0) throw InputError(source, "file is empty");
  if (size > kMaxModelFileBytes)
    throw InputError(source, "file is too large (" + std::to_string(size) + " bytes, limit " +
                                 std::to_string(kMaxModelFileBytes) + ")");
  return size;
}

std::string read_file(const fs::path& path, std::uintmax_t size, const std::string& source) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(source, "cannot open file");
  std::string bytes(static_cast<std::size_t>(size), '\0');
  in.read(bytes.data(), static_cast<std::streamsize>(size));
  bytes.resize(static_cast<std::size_t>(in.gcount()));
  if (bytes.empty()) throw InputError(source, "file is empty");
  return bytes;
}

Format format_of_extension(std::string extension) {
  for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (extension == ".obj") return Format::kObj;
  if (extension == ".ply") return Format::kPly;
  if (extension == ".stl") return Format::kStl;
  return Format::kUnknown;
}

}  // namespace

Mesh load_model(const fs::path& path) {
  const std::string source = path.string();
  const std::uintmax_t size = checked_file_size(path, source);
  const std::string extension = path.extension().string();
  const Format format = format_of_extension(extension);
  std::string bytes = read_file(path, size, source);
  try {
    switch (format) {
      case Format::kObj:
        return load_obj(path, bytes, source);
      case Format::kPly:
        return load_ply(bytes, source);
      case Format::kStl:
        return load_stl(bytes, source);
      case Format::kUnknown:
        break;
    }
  } catch (const std::bad_alloc&) {
    throw InputError(source, "out of memory while loading");
  }
  if (extension.empty())
    throw InputError(source, std::string("unsupported model format (no file extension; ") + kSupported + ")");
  throw InputError(source, "unsupported model format '" + printable(extension) + "' (" + kSupported + ")");
}

}  // namespace facet
