// pcd_loader.cpp - load_pcd(): the Point Cloud Library's PCD files, ASCII, binary and binary_compressed.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <vector>

#if !defined(FACET_NO_LZF)
#include <lzf.h>
#endif

#include "facet/error.hpp"
#include "job/io/loaders.hpp"
#include "job/io/text_scan.hpp"

namespace facet {
namespace {

// PCL's header (pcl/io/pcd_io: "PCD file format"): one keyword per line, the fields' names, sizes in bytes,
// types (F float, I signed, U unsigned) and counts (elements per field), the cloud's width and height, its point
// count, and how the data follows the DATA line.
struct Field {
  std::string name;
  int size = 4;
  char type = 'F';
  std::size_t count = 1;
  std::size_t offset = 0;  // within a binary point; its element index within an ASCII one
};

struct Header {
  std::vector<Field> fields;
  std::size_t points = 0;
  std::size_t point_bytes = 0, point_values = 0;
  std::string data;
  std::size_t body = 0;  // where the data starts in the file
};

constexpr std::size_t kMaxFields = 4096;
constexpr std::size_t kMaxCount = 1 << 16;
constexpr std::size_t kMaxPointBytes = 1 << 20;

std::vector<std::string_view> words(std::string_view line) {
  std::vector<std::string_view> out;
  TextCursor cursor(line.data(), line.data() + line.size(), 0);
  for (std::string_view word = cursor.next(); !word.empty(); word = cursor.next()) out.push_back(word);
  return out;
}

std::size_t count_of(std::string_view word, const std::string& source, std::string_view what, std::size_t limit) {
  std::int64_t value = 0;
  if (!parse_integer(word, value) || value < 0 || static_cast<std::uint64_t>(value) > limit)
    throw InputError(source, std::string(what) + " " + in_quotes(word) + " is not a count from 0 to " +
                                 std::to_string(limit));
  return static_cast<std::size_t>(value);
}

Header read_header(std::string_view bytes, const std::string& source) {
  Header h;
  std::vector<std::string_view> sizes, types, counts;
  std::size_t width = 0, height = 1;
  bool has_points = false, has_width = false;
  for (std::size_t at = 0; at < bytes.size() && h.data.empty();) {
    std::size_t end = bytes.find('\n', at);
    if (end == std::string_view::npos) end = bytes.size();
    const std::vector<std::string_view> w = words(bytes.substr(at, end - at));
    at = end + 1;
    if (w.empty() || w[0][0] == '#') continue;
    const std::string_view key = w[0];
    const std::vector<std::string_view> values(w.begin() + 1, w.end());
    if (values.size() > kMaxFields) throw InputError(source, "more than 4096 fields");
    if (key == "FIELDS" || key == "COLUMNS") {
      for (const std::string_view name : values) h.fields.push_back({std::string(name)});
    } else if (key == "SIZE") {
      sizes = values;
    } else if (key == "TYPE") {
      types = values;
    } else if (key == "COUNT") {
      counts = values;
    } else if (key == "WIDTH" && !values.empty()) {
      width = count_of(values[0], source, "WIDTH", kMaxModelVertices), has_width = true;
    } else if (key == "HEIGHT" && !values.empty()) {
      height = count_of(values[0], source, "HEIGHT", kMaxModelVertices);
    } else if (key == "POINTS" && !values.empty()) {
      h.points = count_of(values[0], source, "POINTS", kMaxModelVertices), has_points = true;
    } else if (key == "DATA") {
      if (values.empty()) throw InputError(source, "DATA names no encoding (ascii, binary or binary_compressed)");
      h.data = std::string(values[0]);
      h.body = at > bytes.size() ? bytes.size() : at;
    } else if (key != "VERSION" && key != "VIEWPOINT") {
      throw InputError(source, "not a PCD header: unknown line " + in_quotes(key));
    }
  }
  if (h.data.empty()) throw InputError(source, "no DATA line: not a PCD file, or its header is cut short");
  if (h.fields.empty()) throw InputError(source, "the header names no FIELDS");
  const std::size_t n = h.fields.size();
  if (sizes.size() != n || types.size() != n || (!counts.empty() && counts.size() != n))
    throw InputError(source, std::to_string(n) + " fields, but SIZE, TYPE or COUNT gives another number");
  for (std::size_t i = 0; i < n; ++i) {
    Field& f = h.fields[i];
    f.size = static_cast<int>(count_of(sizes[i], source, "SIZE", 8));
    if (types[i].size() != 1 || std::string_view("FIU").find(types[i][0]) == std::string_view::npos)
      throw InputError(source, "field " + in_quotes(f.name) + " has TYPE " + in_quotes(types[i]) + " (F, I or U)");
    f.type = types[i][0];
    const bool fits =
        f.type == 'F' ? (f.size == 4 || f.size == 8) : (f.size == 1 || f.size == 2 || f.size == 4 || f.size == 8);
    if (!fits) throw InputError(source, "field " + in_quotes(f.name) + " has SIZE " + std::to_string(f.size) +
                                            " for TYPE " + std::string(1, f.type));
    f.count = counts.empty() ? 1 : count_of(counts[i], source, "COUNT", kMaxCount);
    if (f.count == 0) throw InputError(source, "field " + in_quotes(f.name) + " has COUNT 0");
    f.offset = h.point_bytes;
    h.point_bytes += static_cast<std::size_t>(f.size) * f.count;
    h.point_values += f.count;
    if (h.point_bytes > kMaxPointBytes) throw InputError(source, "a point of more than 1 MiB of fields");
  }
  if (!has_points) {
    if (!has_width) throw InputError(source, "neither POINTS nor WIDTH gives the number of points");
    if (height != 0 && width > kMaxModelVertices / height) throw InputError(source, "more than 2^27 points");
    h.points = width * height;
  }
  return h;
}

// The numbers of one field element in a binary point: any type, as a double.
double binary_value(const unsigned char* p, const Field& f) {
  const auto get = [p]<class T>(T) {
    T v;
    std::memcpy(&v, p, sizeof v);
    return static_cast<double>(v);
  };
  if (f.type == 'F') return f.size == 4 ? get(float{}) : get(double{});
  if (f.type == 'I') {
    switch (f.size) {
      case 1: return get(std::int8_t{});
      case 2: return get(std::int16_t{});
      case 4: return get(std::int32_t{});
      default: return get(std::int64_t{});
    }
  }
  switch (f.size) {
    case 1: return get(std::uint8_t{});
    case 2: return get(std::uint16_t{});
    case 4: return get(std::uint32_t{});
    default: return get(std::uint64_t{});
  }
}

// PCL's packed colour (rgb or rgba): the bits of a 4-byte field, 0xAARRGGBB, written as a float or an unsigned.
glm::vec4 packed_color(std::uint32_t bits) {
  return {static_cast<float>((bits >> 16) & 255u) / 255.0f, static_cast<float>((bits >> 8) & 255u) / 255.0f,
          static_cast<float>(bits & 255u) / 255.0f, 1.0f};
}

// What the cloud's fields give: the first element of each field read, by name.
struct Roles {
  int x = -1, y = -1, z = -1, nx = -1, ny = -1, nz = -1, rgb = -1, intensity = -1;
};

Roles roles_of(const Header& h, const std::string& source) {
  Roles r;
  for (std::size_t i = 0; i < h.fields.size(); ++i) {
    const std::string& name = h.fields[i].name;
    const int index = static_cast<int>(i);
    if (name == "x") r.x = index;
    else if (name == "y") r.y = index;
    else if (name == "z") r.z = index;
    else if (name == "normal_x") r.nx = index;
    else if (name == "normal_y") r.ny = index;
    else if (name == "normal_z") r.nz = index;
    else if ((name == "rgb" || name == "rgba") && h.fields[i].size == 4) r.rgb = index;
    else if (name == "intensity") r.intensity = index;
  }
  if (r.x < 0 || r.y < 0 || r.z < 0) throw InputError(source, "the fields have no x, y and z");
  if (r.nx < 0 || r.ny < 0 || r.nz < 0) r.nx = r.ny = r.nz = -1;
  return r;
}

// Adds one point from its fields' values, unless its position is not a number (PCL's mark of a missing point in an
// organized cloud); `color_bits` is the packed colour's bits where the cloud has one.
template <class Value>
void add_point(const Roles& r, Value value, std::uint32_t color_bits, Mesh& mesh, std::size_t& skipped) {
  const glm::vec3 p(narrow(value(r.x)), narrow(value(r.y)), narrow(value(r.z)));
  if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
    ++skipped;
    return;
  }
  mesh.positions.push_back(p);
  if (r.nx >= 0) mesh.normals.push_back(glm::vec3(narrow(value(r.nx)), narrow(value(r.ny)), narrow(value(r.nz))));
  if (r.rgb >= 0) mesh.colors.push_back(packed_color(color_bits));
  if (r.intensity >= 0) {
    const float intensity = narrow(value(r.intensity));
    mesh.intensities.push_back(std::isfinite(intensity) ? intensity : 0.0f);
  }
}

// Binary points, one after another (binary), or each field's values for every point in turn (binary_compressed,
// once decompressed): field f of point i is at f.offset * points + i * f.size there.
void read_binary(const Header& h, const Roles& r, const unsigned char* data, bool by_field, Mesh& mesh,
                 std::size_t& skipped) {
  const auto at = [&](int field, std::size_t point) {
    const Field& f = h.fields[static_cast<std::size_t>(field)];
    return by_field ? data + f.offset * h.points + point * f.size * f.count : data + point * h.point_bytes + f.offset;
  };
  for (std::size_t i = 0; i < h.points; ++i) {
    std::uint32_t bits = 0;
    if (r.rgb >= 0) std::memcpy(&bits, at(r.rgb, i), sizeof bits);
    add_point(
        r, [&](int field) { return binary_value(at(field, i), h.fields[static_cast<std::size_t>(field)]); }, bits, mesh,
        skipped);
  }
}

void read_ascii(const Header& h, const Roles& r, std::string_view text, const std::string& source, Mesh& mesh,
                std::size_t& skipped) {
  std::vector<std::size_t> first(h.fields.size());  // each field's first value within a point's
  for (std::size_t i = 0, at = 0; i < h.fields.size(); ++i) first[i] = at, at += h.fields[i].count;
  std::vector<double> values(h.point_values);
  TextCursor cursor(text.data(), text.data() + text.size(), 0);
  for (std::size_t point = 0; point < h.points; ++point) {
    for (double& v : values) {
      const std::string_view token = cursor.next();
      if (token.empty())
        throw InputError(source, "the data ends after " + std::to_string(point) + " of " +
                                     std::to_string(h.points) + " points");
      // PCL writes a missing value as nan; parse_real reads finite numbers and inf only.
      if (token == "nan" || token == "NaN" || token == "-nan") v = std::nan("");
      else if (!parse_real(token, v)) throw InputError(source, "point " + std::to_string(point) + ": " +
                                                                   in_quotes(token) + " is not a number");
    }
    std::uint32_t bits = 0;
    if (r.rgb >= 0) {
      const Field& f = h.fields[static_cast<std::size_t>(r.rgb)];
      const double c = values[first[static_cast<std::size_t>(r.rgb)]];
      // A float field holds the colour's bits as a float; an unsigned one, as the number.
      if (f.type == 'F') {
        const float as_float = static_cast<float>(c);
        std::memcpy(&bits, &as_float, sizeof bits);
      } else {
        bits = c >= 0.0 && c <= 4294967295.0 ? static_cast<std::uint32_t>(c) : 0u;  // NaN and out of range: black
      }
    }
    add_point(r, [&](int field) { return values[first[static_cast<std::size_t>(field)]]; }, bits, mesh, skipped);
  }
}

}  // namespace

Mesh load_pcd(std::string_view bytes, const std::string& source) {
  const Header h = read_header(bytes, source);
  const Roles roles = roles_of(h, source);
  const std::string_view body = bytes.substr(h.body);
  Mesh mesh;
  std::size_t skipped = 0;
  const auto reserve = [&] {
    mesh.positions.reserve(h.points);
    if (roles.nx >= 0) mesh.normals.reserve(h.points);
    if (roles.rgb >= 0) mesh.colors.reserve(h.points);
    if (roles.intensity >= 0) mesh.intensities.reserve(h.points);
  };
  const auto* data = reinterpret_cast<const unsigned char*>(body.data());
  // Each check bounds what a header may make the reader allocate by the bytes that follow it.
  const std::uint64_t need = std::uint64_t{h.points} * h.point_bytes;
  if (h.data == "ascii") {
    // A value takes at least one character and a separator.
    if (std::uint64_t{h.points} * h.point_values * 2 > body.size() + 1)
      throw InputError(source, "truncated: " + std::to_string(h.points) + " points of " +
                                   std::to_string(h.point_values) + " values in " + std::to_string(body.size()) +
                                   " bytes of text");
    reserve();
    read_ascii(h, roles, body, source, mesh, skipped);
  } else if (h.data == "binary") {
    if (need > body.size())
      throw InputError(source, "truncated: " + std::to_string(h.points) + " points of " +
                                   std::to_string(h.point_bytes) + " bytes need " + std::to_string(need) + ", " +
                                   std::to_string(body.size()) + " follow the header");
    reserve();
    read_binary(h, roles, data, false, mesh, skipped);
  } else if (h.data == "binary_compressed") {
#if defined(FACET_NO_LZF)
    throw InputError(source, "binary_compressed PCD data is not read in this build (no LZF)");
#else
    std::uint32_t sizes[2];
    if (body.size() < sizeof sizes) throw InputError(source, "truncated: no compressed sizes after the header");
    std::memcpy(sizes, data, sizeof sizes);
    const std::uint64_t compressed = sizes[0], expanded = sizes[1];
    if (compressed > body.size() - sizeof sizes)
      throw InputError(source, "truncated: " + std::to_string(compressed) + " compressed bytes declared, " +
                                   std::to_string(body.size() - sizeof sizes) + " follow");
    if (expanded != need)
      throw InputError(source, "the compressed data expands to " + std::to_string(expanded) + " bytes, where " +
                                   std::to_string(h.points) + " points of " + std::to_string(h.point_bytes) +
                                   " bytes need " + std::to_string(need));
    // LZF expands 3 bytes to at most 264: a larger claim is a lie, refused before anything is allocated.
    if (expanded / 88 > compressed + 1) throw InputError(source, "the compressed data cannot expand to its claim");
    std::vector<unsigned char> plain(static_cast<std::size_t>(expanded));
    if (expanded > 0 &&
        lzf_decompress(data + sizeof sizes, static_cast<unsigned>(compressed), plain.data(),
                       static_cast<unsigned>(expanded)) != expanded)
      throw InputError(source, "the compressed data is corrupt");
    reserve();
    read_binary(h, roles, plain.data(), true, mesh, skipped);
#endif
  } else {
    throw InputError(source, "DATA " + in_quotes(h.data) + " (ascii, binary or binary_compressed)");
  }
  if (mesh.positions.empty())
    throw InputError(source, "nothing to draw (" + std::to_string(h.points) + " points, none with a position)");
  if (skipped > 0) warn(source, "skipped " + std::to_string(skipped) + " points without a position (NaN)");
  mesh.points_at_every_vertex();
  validate(mesh, source);
  return mesh;
}

}  // namespace facet
