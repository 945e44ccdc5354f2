// ply_header.cpp - parse_header(): the PLY header's lines, strictly checked, and its counts against the file's size.
#include "job/io/ply_header.hpp"

#include <algorithm>
#include <charconv>
#include <optional>

#include "facet/error.hpp"
#include "job/io/loaders.hpp"
#include "job/io/text_scan.hpp"

namespace facet::ply {

const char* type_name(Type t) {
  constexpr const char* kNames[] = {"char", "uchar", "short", "ushort", "int", "uint", "float", "double"};
  return kNames[static_cast<int>(t)];
}

namespace {

// Both spellings of each type: the original (char, uchar, ...) and the sized one (int8, uint8, ...).
std::optional<Type> parse_type(std::string_view name) {
  struct Spelling {
    std::string_view name;
    Type type;
  };
  constexpr Spelling kSpellings[] = {
      {"char", Type::kInt8},     {"int8", Type::kInt8},       {"uchar", Type::kUInt8},    {"uint8", Type::kUInt8},
      {"short", Type::kInt16},   {"int16", Type::kInt16},     {"ushort", Type::kUInt16},  {"uint16", Type::kUInt16},
      {"int", Type::kInt32},     {"int32", Type::kInt32},     {"uint", Type::kUInt32},    {"uint32", Type::kUInt32},
      {"float", Type::kFloat32}, {"float32", Type::kFloat32}, {"double", Type::kFloat64}, {"float64", Type::kFloat64}};
  for (const Spelling& s : kSpellings)
    if (s.name == name) return s.type;
  return std::nullopt;
}

// The first words of a header line: no keyword takes more than five, and a comment may be as long as the file.
std::vector<std::string_view> words(std::string_view line) {
  std::vector<std::string_view> out;
  TextCursor in(line.data(), line.data() + line.size(), 1);
  for (std::string_view w = in.next(); !w.empty() && out.size() < 6; w = in.next()) out.push_back(w);
  return out;
}

class HeaderParser {
 public:
  HeaderParser(std::string_view bytes, const std::string& source) : bytes_(bytes), source_(source) {}

  Header parse() {
    std::size_t pos = 0;
    bool ended = false;
    while (pos < bytes_.size() && !ended) {
      const std::size_t end = std::min(bytes_.find('\n', pos), bytes_.size());
      const std::string_view line = bytes_.substr(pos, end - pos);
      pos = std::min(end + 1, bytes_.size());
      ++line_;
      ended = parse_line(line);
    }
    if (!ended) throw InputError(source_, "the PLY header has no 'end_header' line (truncated?)");
    if (!have_format_) throw InputError(source_, "the PLY header has no 'format' line");
    if (skipped_ > 0)
      warn(source_, "skipped " + std::to_string(skipped_) + " unknown PLY header line(s), the first on line " +
                        std::to_string(first_skipped_) + ": " + in_quotes(skipped_text_));
    header_.body_offset = pos;
    header_.body_line = line_ + 1;
    return std::move(header_);
  }

 private:
  [[noreturn]] void fail(const std::string& problem) const {
    throw InputError(source_, "PLY header line " + std::to_string(line_) + ": " + problem);
  }

  // Returns true at "end_header".
  bool parse_line(std::string_view line) {
    const std::vector<std::string_view> w = words(line);
    if (line_ == 1) {
      if (w.size() != 1 || w[0] != "ply") throw InputError(source_, "not a PLY file (the first line is not 'ply')");
      return false;
    }
    if (w.empty() || w[0] == "comment" || w[0] == "obj_info") return false;
    if (w[0] == "format") {
      parse_format(w);
    } else if (w[0] == "element") {
      parse_element(w);
    } else if (w[0] == "property") {
      parse_property(w);
    } else if (w[0] == "end_header") {
      if (w.size() != 1) fail("text after 'end_header'");
      return true;
    } else {
      if (skipped_++ == 0) {
        first_skipped_ = line_;
        skipped_text_ = std::string(line.substr(0, 60));
      }
    }
    return false;
  }

  void parse_format(const std::vector<std::string_view>& w) {
    if (have_format_) fail("a second 'format' line");
    if (w.size() != 3) fail("expected 'format <encoding> 1.0'");
    if (w[1] == "ascii") header_.encoding = Encoding::kAscii;
    else if (w[1] == "binary_little_endian") header_.encoding = Encoding::kBinaryLittleEndian;
    else if (w[1] == "binary_big_endian") header_.encoding = Encoding::kBinaryBigEndian;
    else fail("unknown encoding " + in_quotes(w[1]) + " (ascii, binary_little_endian or binary_big_endian)");
    if (w[2] != "1.0") fail("unsupported PLY version " + in_quotes(w[2]) + " (only 1.0)");
    have_format_ = true;
  }

  void parse_element(const std::vector<std::string_view>& w) {
    if (w.size() != 3) fail("expected 'element <name> <count>'");
    Element e;
    e.name = std::string(w[1]);
    const char* end = w[2].data() + w[2].size();
    const auto [ptr, ec] = std::from_chars(w[2].data(), end, e.count);
    if (ec != std::errc() || ptr != end) fail("element count " + in_quotes(w[2]) + " is not a non-negative integer");
    for (const Element& other : header_.elements)
      if (other.name == e.name) fail("a second element named " + in_quotes(e.name));
    header_.elements.push_back(std::move(e));
  }

  Type type(std::string_view name) const {
    const std::optional<Type> t = parse_type(name);
    if (!t) fail("unknown property type " + in_quotes(name));
    return *t;
  }

  void parse_property(const std::vector<std::string_view>& w) {
    if (header_.elements.empty()) fail("a property before any element");
    Property p;
    if (w.size() == 5 && w[1] == "list") {
      p.list = true;
      p.count_type = type(w[2]);
      if (!is_integer(p.count_type)) fail("list count type " + in_quotes(w[2]) + " is not an integer type");
      p.type = type(w[3]);
      p.name = std::string(w[4]);
    } else if (w.size() == 3 && w[1] != "list") {
      p.type = type(w[1]);
      p.name = std::string(w[2]);
    } else {
      fail("expected 'property <type> <name>' or 'property list <count type> <type> <name>'");
    }
    Element& e = header_.elements.back();
    for (const Property& other : e.properties)
      if (other.name == p.name)
        fail("element " + in_quotes(e.name) + " has a second property named " + in_quotes(p.name));
    e.properties.push_back(std::move(p));
  }

  std::string_view bytes_;
  const std::string& source_;
  Header header_;
  std::size_t line_ = 0;
  bool have_format_ = false;
  std::size_t skipped_ = 0, first_skipped_ = 0;
  std::string skipped_text_;
};

}  // namespace

Header parse_header(std::string_view bytes, const std::string& source) { return HeaderParser(bytes, source).parse(); }

void check_counts(const Header& header, std::size_t body_bytes, const std::string& source) {
  const bool ascii = header.encoding == Encoding::kAscii;
  std::uint64_t left = ascii ? body_bytes + 1 : body_bytes;  // the last ASCII value needs no separator
  for (const Element& e : header.elements) {
    std::uint64_t least = 0;
    for (const Property& p : e.properties) least += ascii ? 2 : size_of(p.list ? p.count_type : p.type);
    if (least == 0) continue;
    if (e.count > left / least)
      throw InputError(source, "PLY element " + in_quotes(e.name) + " claims " + std::to_string(e.count) +
                                   " entries of at least " + std::to_string(least) + " bytes each, but only " +
                                   std::to_string(body_bytes) + " bytes follow the header (truncated?)");
    left -= e.count * least;
  }
}

}  // namespace facet::ply
