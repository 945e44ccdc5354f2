// obj_parse.cpp - parse_obj(): one pass over an OBJ file's lines into flat arrays, no per-line allocation.
#include "job/io/obj_parse.hpp"

#include <algorithm>
#include <charconv>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <set>
#include <string>
#include <system_error>

#include "facet/error.hpp"
#include "job/io/loaders.hpp"
#include "job/io/text_scan.hpp"

namespace facet {
namespace {

bool is_blank(char c) { return c == ' ' || c == '\t'; }
bool is_digit(char c) { return static_cast<unsigned>(c - '0') < 10u; }

// The part of a line after its keyword: [p, end), the line break excluded.
struct LineRest {
  const char* p;
  const char* end;

  void skip_blanks() {
    while (p != end && is_blank(*p)) ++p;
  }
  // The next word: blanks skipped, then everything up to the next blank.
  std::string_view word() {
    skip_blanks();
    const char* start = p;
    while (p != end && !is_blank(*p)) ++p;
    return {start, static_cast<std::size_t>(p - start)};
  }
  // Moves to the next '/', blank or the end (where an index's digits stop being read).
  void skip_to_separator() {
    while (p != end && *p != '/' && !is_blank(*p)) ++p;
  }
};

// The number a word starts with, read as strtof reads a decimal number (what follows it is ignored); false if the
// word does not start with one. Words starting with a letter ("nan", "inf") are not numbers here.
bool read_real(std::string_view word, float& out) {
  const char* s = word.data();
  const char* const e = s + word.size();
  bool negative = false;
  if (s != e && (*s == '+' || *s == '-')) negative = *s++ == '-';
  if (s == e || !(is_digit(*s) || *s == '.')) return false;
  // The number's extent: digits, a fraction, an exponent. An "e" without digits after it (or with more than nine)
  // makes the word no number at all, as OBJ tools built on tinyobjloader read it.
  const char* q = s;
  while (q != e && is_digit(*q)) ++q;
  if (q != e && *q == '.') {
    ++q;
    while (q != e && is_digit(*q)) ++q;
  }
  if (q != e && (*q == 'e' || *q == 'E')) {
    ++q;
    if (q != e && (*q == '+' || *q == '-')) ++q;
    const char* digits = q;
    while (q != e && is_digit(*q)) ++q;
    if (q == digits || q - digits > 9) return false;
  }
  float value = 0.0f;
#if defined(__cpp_lib_to_chars)
  const auto [stop, ec] = std::from_chars(s, q, value, std::chars_format::general);
  (void)stop;
  if (ec == std::errc::result_out_of_range) {
    // Beyond float's range: infinity, or zero or a denormal, as strtof gives them.
    value = std::strtof(std::string(s, q).c_str(), nullptr);
  } else if (ec != std::errc()) {
    value = 0.0f;  // a lone "." or ".e5": zero, as a parser reading digit by digit makes of it
  }
#else
  value = std::strtof(std::string(s, q).c_str(), nullptr);
#endif
  out = negative ? -value : value;
  return true;
}

// An index as C's atoi reads it with glibc: whitespace, a sign, digits (none: 0), saturated to 64 bits and then
// truncated to int, so that a file's indices mean what every tinyobj-based tool reads in them.
std::int32_t read_int(LineRest& line) {
  const char* p = line.p;
  while (p != line.end && is_space(*p)) ++p;
  bool negative = false;
  if (p != line.end && (*p == '+' || *p == '-')) negative = *p++ == '-';
  std::uint64_t magnitude = 0;
  bool saturated = false;
  for (; p != line.end && is_digit(*p); ++p) {
    if (magnitude > (std::numeric_limits<std::uint64_t>::max() - 9) / 10) saturated = true;
    else magnitude = magnitude * 10 + static_cast<unsigned>(*p - '0');
  }
  constexpr std::uint64_t kMax = std::numeric_limits<std::int64_t>::max();
  std::int64_t value;
  if (negative)
    value = saturated || magnitude > kMax ? std::numeric_limits<std::int64_t>::min()
                                          : -static_cast<std::int64_t>(magnitude);
  else
    value = saturated || magnitude > kMax ? std::numeric_limits<std::int64_t>::max()
                                          : static_cast<std::int64_t>(magnitude);
  return static_cast<std::int32_t>(value);  // C++20: modulo 2^32, as the C conversion does
}

// OBJ numbers from 1; a negative index counts back from the last element read so far; 0 is no index.
bool fix_index(std::int32_t index, std::int32_t count, std::int32_t& out) {
  if (index == 0) return false;
  out = index > 0 ? index - 1 : count + index;
  return true;
}

// One corner: "v", "v/vt", "v//vn" or "v/vt/vn". The scan restarts after each number at the next separator, so
// "1x/2" reads as "1/2".
bool read_corner(LineRest& line, std::int32_t v_count, std::int32_t vt_count, std::int32_t vn_count, ObjCorner& c) {
  c = {-1, -1, -1};
  if (!fix_index(read_int(line), v_count, c.v)) return false;
  line.skip_to_separator();
  if (line.p == line.end || *line.p != '/') return true;
  ++line.p;
  if (line.p != line.end && *line.p == '/') {
    ++line.p;
    if (!fix_index(read_int(line), vn_count, c.vn)) return false;
    line.skip_to_separator();
    return true;
  }
  if (!fix_index(read_int(line), vt_count, c.vt)) return false;
  line.skip_to_separator();
  if (line.p == line.end || *line.p != '/') return true;
  ++line.p;
  if (!fix_index(read_int(line), vn_count, c.vn)) return false;
  line.skip_to_separator();
  return true;
}

bool spells_non_finite(std::string_view word) {
  if (!word.empty() && (word[0] == '+' || word[0] == '-')) word.remove_prefix(1);
  if (word.size() < 3) return false;
  char head[3];
  for (int i = 0; i < 3; ++i) head[i] = static_cast<char>(word[static_cast<std::size_t>(i)] | 0x20);  // lower case
  return std::memcmp(head, "nan", 3) == 0 || std::memcmp(head, "inf", 3) == 0;  // also "infinity", "nan(...)"
}

// The names an `mtllib` line lists: split at spaces, a backslash making the next character part of a name; the
// last (possibly empty) name is always listed.
std::vector<std::string> library_names(std::string_view rest) {
  std::vector<std::string> names;
  std::string name;
  bool escaped = false;
  for (const char c : rest) {
    if (escaped) {
      escaped = false;
    } else if (c == '\\') {
      escaped = true;
      continue;
    } else if (c == ' ') {
      if (!name.empty()) names.push_back(name);
      name.clear();
      continue;
    }
    name += c;
  }
  names.push_back(name);
  return names;
}

class Parser {
 public:
  Parser(const ObjMaterialReader& read_materials, const std::string& source, std::size_t lines)
      : read_materials_(read_materials), source_(source) {
    out_.positions.reserve(3 * lines);
    out_.normals.reserve(3 * lines);
    out_.uvs.reserve(2 * lines);
    out_.corners.reserve(3 * lines);
    out_.face_ends.reserve(lines);
    out_.face_materials.reserve(lines);
  }

  void line(LineRest rest) {
    rest.skip_blanks();
    if (rest.p == rest.end) return;
    const char* k = rest.p;
    const std::size_t size = static_cast<std::size_t>(rest.end - k);
    const auto keyword = [&](std::string_view word) {
      return size > word.size() && std::memcmp(k, word.data(), word.size()) == 0 && is_blank(k[word.size()]);
    };
    if (keyword("v")) return vertex({k + 2, rest.end});
    if (keyword("vn")) return read_reals({k + 3, rest.end}, out_.normals, 3);
    if (keyword("vt")) return read_reals({k + 3, rest.end}, out_.uvs, 2);
    if (keyword("f")) return face({k + 2, rest.end});
    if (keyword("l") || keyword("p")) return check_indices({k + 2, rest.end}, *k);
    if (size >= 6 && std::memcmp(k, "usemtl", 6) == 0) return use_material({k + 6, rest.end});
    if (keyword("mtllib")) return load_libraries({k + 7, rest.end});
    // Groups, objects, smoothing groups and anything unknown change nothing facet draws.
  }

  ObjData finish() {
    if (!all_colors_) out_.colors.clear();
    return std::move(out_);
  }

  std::size_t line_number = 0;

 private:
  [[noreturn]] void malformed(char element) const {
    throw InputError(source_, std::string("malformed '") + element + "' element on line " +
                                  std::to_string(line_number) + " (an index is 0 or not a number)");
  }

  void vertex(LineRest rest) {
    for (int axis = 0; axis < 3; ++axis) {
      const std::string_view word = rest.word();
      float value = 0.0f;
      if (!read_real(word, value) && spells_non_finite(word))
        throw InputError(source_, "non-finite vertex position on line " + std::to_string(line_number));
      out_.positions.push_back(value);
    }
    float rgb[3];
    const bool has_color = read_real(rest.word(), rgb[0]) && read_real(rest.word(), rgb[1]) &&
                           read_real(rest.word(), rgb[2]);
    all_colors_ = all_colors_ && has_color;
    if (all_colors_) out_.colors.insert(out_.colors.end(), rgb, rgb + 3);
  }

  static void read_reals(LineRest rest, std::vector<float>& out, int count) {
    for (int i = 0; i < count; ++i) {
      float value = 0.0f;
      read_real(rest.word(), value);
      out.push_back(value);
    }
  }

  std::int32_t count(const std::vector<float>& values, std::size_t per) const {
    return static_cast<std::int32_t>(values.size() / per);
  }

  void face(LineRest rest) {
    rest.skip_blanks();
    const std::size_t first = out_.corners.size();
    const std::int32_t v = count(out_.positions, 3), vt = count(out_.uvs, 2), vn = count(out_.normals, 3);
    while (rest.p != rest.end) {
      ObjCorner corner;
      if (!read_corner(rest, v, vt, vn, corner)) malformed('f');
      out_.corners.push_back(corner);
      rest.skip_blanks();
    }
    const std::size_t corners = out_.corners.size() - first;
    if (corners < 3) {
      out_.corners.resize(first);
      ++out_.dropped_faces;
      return;
    }
    out_.face_ends.push_back(static_cast<std::uint32_t>(out_.corners.size()));
    out_.face_materials.push_back(material_);
  }

  // Lines and points are not drawn, but their indices are checked as a face's are.
  void check_indices(LineRest rest, char element) const {
    const std::int32_t v = count(out_.positions, 3), vt = count(out_.uvs, 2), vn = count(out_.normals, 3);
    while (rest.p != rest.end) {
      ObjCorner corner;
      if (!read_corner(rest, v, vt, vn, corner)) malformed(element);
      rest.skip_blanks();
    }
  }

  void use_material(LineRest rest) {
    const std::string_view name = rest.word();
    const auto found = material_names_.find(std::string(name));
    material_ = found != material_names_.end() ? found->second : -1;
  }

  void load_libraries(LineRest rest) {
    for (const std::string& name : library_names({rest.p, static_cast<std::size_t>(rest.end - rest.p)})) {
      // A library read before is passed over, and the next name tried, as tinyobjloader does.
      if (loaded_libraries_.count(name)) continue;
      if (read_materials_ && read_materials_(name, material_names_)) {
        loaded_libraries_.insert(name);
        return;
      }
    }
  }

  const ObjMaterialReader& read_materials_;
  const std::string& source_;
  ObjData out_;
  bool all_colors_ = true;
  std::int32_t material_ = -1;
  std::map<std::string, int> material_names_;
  std::set<std::string> loaded_libraries_;
};

}  // namespace

ObjData parse_obj(std::string_view text, const ObjMaterialReader& read_materials, const std::string& source) {
  // Room for as many elements as the file has lines, so that the arrays are not moved as they grow (each move
  // would also fault in fresh pages); room that is never written is never touched.
  const std::size_t lines = static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n')) + 1;
  Parser parser(read_materials, source, lines);
  // A NUL ends a line's text, as it ends a C string; most files have none, and then no line needs the check.
  const bool has_nul = std::memchr(text.data(), '\0', text.size()) != nullptr;
  const char* p = text.data();
  const char* const end = p + text.size();
  while (p != end) {
    const char* newline = static_cast<const char*>(std::memchr(p, '\n', static_cast<std::size_t>(end - p)));
    if (!newline) newline = end;
    const char* cr = static_cast<const char*>(std::memchr(p, '\r', static_cast<std::size_t>(newline - p)));
    const char* line_end = cr ? cr : newline;
    const char* next = cr ? cr + 1 + (cr + 1 != end && cr[1] == '\n') : newline + (newline != end);
    if (has_nul) {
      if (const void* nul = std::memchr(p, '\0', static_cast<std::size_t>(line_end - p)))
        line_end = static_cast<const char*>(nul);
    }
    ++parser.line_number;
    parser.line({p, line_end});
    p = next;
  }
  return parser.finish();
}

}  // namespace facet
