// ply_header.hpp - the PLY header (format, elements and their properties) as ply_header.cpp parses and checks it.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace facet::ply {

enum class Type : std::uint8_t { kInt8, kUInt8, kInt16, kUInt16, kInt32, kUInt32, kFloat32, kFloat64 };

constexpr std::size_t size_of(Type t) {
  constexpr std::size_t kSizes[] = {1, 1, 2, 2, 4, 4, 4, 8};
  return kSizes[static_cast<int>(t)];
}
constexpr bool is_integer(Type t) { return t < Type::kFloat32; }
const char* type_name(Type t);

struct Property {
  std::string name;
  Type type = Type::kFloat32;  // of the value, or of each entry of a list
  bool list = false;
  Type count_type = Type::kUInt8;  // lists only
};

struct Element {
  std::string name;
  std::uint64_t count = 0;
  std::vector<Property> properties;
};

enum class Encoding { kAscii, kBinaryLittleEndian, kBinaryBigEndian };

struct Header {
  Encoding encoding = Encoding::kAscii;
  std::vector<Element> elements;
  std::size_t body_offset = 0;  // first byte after the "end_header" line
  std::size_t body_line = 1;    // that byte's line number, for ASCII messages
};

// Parses the header. Throws InputError(source, ...) naming the header line for anything malformed. Lines that are
// not PLY keywords are skipped with one warning (Blender 2.4 wrote its credit line without "comment").
Header parse_header(std::string_view bytes, const std::string& source);

// Checks that the elements' counts fit in the body_bytes after the header, each entry taking at least its scalars
// and list counts in binary, or two characters per scalar or list count in ASCII; so nothing is allocated for a
// header that lies about its counts. Elements without properties take no bytes and may have any count.
void check_counts(const Header& header, std::size_t body_bytes, const std::string& source);

}  // namespace facet::ply
