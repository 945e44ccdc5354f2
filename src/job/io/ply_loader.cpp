// ply_loader.cpp - load_ply(): PLY in ASCII and both binary byte orders; vertices and faces read, other data skipped.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <optional>
#include <string>
#include <system_error>
#include <thread>
#include <type_traits>
#include <vector>

#include "facet/detail/bits.hpp"
#include "facet/error.hpp"
#include "job/io/loaders.hpp"
#include "job/io/ply_header.hpp"
#include "job/io/splat_loader.hpp"
#include "job/io/text_scan.hpp"

namespace facet {
namespace {

using ply::Element;
using ply::Property;
using ply::Type;

// Ear clipping is quadratic in the corner count; real polygons have a few dozen corners at most.
constexpr std::int64_t kMaxCorners = 1024;

// Thrown by the readers; the element loop (for_each_entry) adds which entry of which element, and where.
struct Problem {
  std::string what;
};
struct EndOfData {};

// Binary bodies, in the file's byte order (kSwap when it is not the machine's). Every read is bounds-checked.
template <bool kSwap>
class BinaryReader {
 public:
  BinaryReader(const char* begin, const char* at, const char* end) : begin_(begin), p_(at), last_(at), end_(end) {}

  double scalar(Type t) {
    switch (t) {
      case Type::kFloat32: return detail::bit_cast<float>(load<std::uint32_t>());
      case Type::kFloat64: return detail::bit_cast<double>(load<std::uint64_t>());
      default: return static_cast<double>(integer(t));
    }
  }

  std::int64_t integer(Type t) {
    switch (t) {
      case Type::kInt8: return static_cast<std::int8_t>(load<std::uint8_t>());
      case Type::kUInt8: return load<std::uint8_t>();
      case Type::kInt16: return static_cast<std::int16_t>(load<std::uint16_t>());
      case Type::kUInt16: return load<std::uint16_t>();
      case Type::kInt32: return static_cast<std::int32_t>(load<std::uint32_t>());
      case Type::kUInt32: return load<std::uint32_t>();
      default: throw Problem{std::string("a ") + ply::type_name(t) + " where an integer is needed"};
    }
  }

  // Whether n values of type t are left in the file.
  bool fits(std::int64_t n, Type t) const {
    return static_cast<std::uint64_t>(n) <= static_cast<std::size_t>(end_ - p_) / ply::size_of(t);
  }

  void skip(const Property& p) {
    if (!p.list) return advance(ply::size_of(p.type));
    const std::int64_t n = count(p.count_type);
    if (!fits(n, p.type)) throw Problem{"a list of " + std::to_string(n) + " entries runs past the end of the file"};
    advance(static_cast<std::size_t>(n) * ply::size_of(p.type));
  }

  std::int64_t count(Type t) {
    const std::int64_t n = integer(t);
    if (n < 0) throw Problem{"negative list count " + std::to_string(n)};
    return n;
  }

  static std::size_t least_bytes(Type t) { return ply::size_of(t); }
  std::string where() const { return "byte offset " + std::to_string(last_ - begin_); }
  std::string trailing() {
    return p_ == end_ ? std::string() : std::to_string(end_ - p_) + " bytes after the last element";
  }

 private:
  template <class T>
  T load() {
    T v;
    if (static_cast<std::size_t>(end_ - p_) < sizeof v) throw EndOfData{};
    std::memcpy(&v, p_, sizeof v);
    last_ = p_;
    p_ += sizeof v;
    if constexpr (kSwap && sizeof v == 2) v = __builtin_bswap16(v);
    if constexpr (kSwap && sizeof v == 4) v = __builtin_bswap32(v);
    if constexpr (kSwap && sizeof v == 8) v = __builtin_bswap64(v);
    return v;
  }

  void advance(std::size_t n) {
    if (static_cast<std::size_t>(end_ - p_) < n) throw EndOfData{};
    last_ = p_;
    p_ += n;
  }

  const char* begin_;
  const char* p_;
  const char* last_;  // where the value being read starts, for messages
  const char* end_;
};

// ASCII bodies: whitespace-separated tokens (line breaks are not checked), each value parsed as its property's type.
class AsciiReader {
 public:
  AsciiReader(const char* at, const char* end, std::size_t line) : in_(at, end, line) {}

  double scalar(Type t) {
    if (ply::is_integer(t)) return static_cast<double>(integer(t));
    const std::string_view token = next();
    if (t == Type::kFloat32) {
      float f;
      if (parse_real(token, f)) return f;
    } else {
      double d;
      if (parse_real(token, d)) return d;
    }
    throw Problem{in_quotes(token) + " is not a number"};
  }

  std::int64_t integer(Type t) {
    struct Range {
      std::int64_t min, max;
    };
    constexpr Range kRanges[] = {{-128, 127},    {0, 255}, {-32768, 32767}, {0, 65535}, {INT32_MIN, INT32_MAX},
                                 {0, UINT32_MAX}};
    const std::string_view token = next();
    std::int64_t v;
    if (!ply::is_integer(t) || !parse_integer(token, v)) throw Problem{in_quotes(token) + " is not an integer"};
    const Range r = kRanges[static_cast<int>(t)];
    if (v < r.min || v > r.max) throw Problem{std::to_string(v) + " does not fit its type, " + ply::type_name(t)};
    return v;
  }

  // Whether n more values could be in the text (each takes a character and, but for the last, a separator).
  bool fits(std::int64_t n, Type) const { return static_cast<std::uint64_t>(n) <= (in_.remaining() + 1) / 2; }

  void skip(const Property& p) {
    if (!p.list) {
      scalar(p.type);
      return;
    }
    for (std::int64_t n = count(p.count_type); n > 0; --n) scalar(p.type);
  }

  std::int64_t count(Type t) {
    const std::int64_t n = integer(t);
    if (n < 0) throw Problem{"negative list count " + std::to_string(n)};
    return n;
  }

  static std::size_t least_bytes(Type) { return 2; }
  // Whether only whitespace is left.
  bool exhausted() { return in_.at_end(); }
  std::string where() const { return "line " + std::to_string(in_.line()); }
  std::string trailing() { return in_.at_end() ? std::string() : "text after the last element, from " + where(); }

 private:
  std::string_view next() {
    const std::string_view token = in_.next();
    if (token.empty()) throw EndOfData{};
    return token;
  }

  TextCursor in_;
};

// What each vertex property feeds; the first property of each role wins and later ones are skipped.
enum Role : std::uint8_t { kX, kY, kZ, kNx, kNy, kNz, kRed, kGreen, kBlue, kAlpha, kU, kV, kIntensity, kRoleCount, kSkip };

Role role_of(std::string_view name) {
  struct Name {
    std::string_view name;
    Role role;
  };
  constexpr Name kNames[] = {{"x", kX},
                             {"y", kY},
                             {"z", kZ},
                             {"nx", kNx},
                             {"ny", kNy},
                             {"nz", kNz},
                             {"red", kRed},
                             {"green", kGreen},
                             {"blue", kBlue},
                             {"alpha", kAlpha},
                             {"s", kU},
                             {"t", kV},
                             {"u", kU},
                             {"v", kV},
                             {"texture_u", kU},
                             {"texture_v", kV},
                             {"texture_s", kU},
                             {"texture_t", kV},
                             {"diffuse_red", kRed},
                             {"diffuse_green", kGreen},
                             {"diffuse_blue", kBlue},
                             {"diffuse_alpha", kAlpha},
                             {"intensity", kIntensity},
                             {"Intensity", kIntensity},
                             {"scalar_intensity", kIntensity},
                             {"scalar_Intensity", kIntensity}};
  for (const Name& n : kNames)
    if (n.name == name) return n.role;
  return kSkip;
}

struct VertexPlan {
  std::vector<Role> roles;       // one per property
  std::vector<double> divisors;  // integer colours are scaled to [0, 1] by their type's maximum; the rest by 1
  bool normals = false, colors = false, uvs = false, intensities = false;
};

VertexPlan plan_vertices(const Element& e, const std::string& source) {
  VertexPlan plan;
  bool seen[kRoleCount] = {};
  for (const Property& p : e.properties) {
    Role role = role_of(p.name);
    if (role != kSkip && (p.list || seen[role])) {
      if (p.list && role <= kZ) throw InputError(source, "PLY vertex property " + in_quotes(p.name) + " is a list");
      role = kSkip;
    }
    if (role != kSkip) seen[role] = true;
    constexpr double kMax[] = {127, 255, 32767, 65535, 2147483647.0, 4294967295.0, 1, 1};
    const bool color = role >= kRed && role <= kAlpha;
    plan.roles.push_back(role);
    plan.divisors.push_back(color ? kMax[static_cast<int>(p.type)] : 1.0);
  }
  for (const char* axis : {"x", "y", "z"})
    if (!seen[role_of(axis)])
      throw InputError(source, std::string("PLY vertex element has no '") + axis + "' property");
  plan.normals = seen[kNx] && seen[kNy] && seen[kNz];
  plan.colors = seen[kRed] && seen[kGreen] && seen[kBlue];
  plan.uvs = seen[kU] && seen[kV];
  plan.intensities = seen[kIntensity];
  return plan;
}

// The face's corner list: "vertex_indices" (or "vertex_index"), a list of integers.
std::size_t plan_faces(const Element& e, const std::string& source) {
  for (std::size_t j = 0; j < e.properties.size(); ++j) {
    const Property& p = e.properties[j];
    if (p.name != "vertex_indices" && p.name != "vertex_index") continue;
    if (!p.list) throw InputError(source, "PLY face property " + in_quotes(p.name) + " is not a list");
    if (!ply::is_integer(p.type))
      throw InputError(source, "PLY face property " + in_quotes(p.name) + " has entries of type " +
                                   ply::type_name(p.type) + " (vertex indices must be integers)");
    return j;
  }
  throw InputError(source, "PLY face element has no 'vertex_indices' list");
}

template <class Reader, class ReadOne>
void for_each_entry(Reader& in, const Element& e, const std::string& source, ReadOne&& read_one) {
  if (e.properties.empty()) return;  // such entries take no bytes: nothing to read, however many there are
  std::uint64_t i = 0;
  try {
    for (; i < e.count; ++i) read_one();
  } catch (const EndOfData&) {
    throw InputError(source, "file ends after " + std::to_string(i) + " of the " + std::to_string(e.count) + " " +
                                 printable(e.name) + " entries (" + in.where() + ")");
  } catch (const Problem& p) {
    throw InputError(source, printable(e.name) + " " + std::to_string(i) + ": " + p.what + " (" + in.where() + ")");
  }
}

template <class Reader>
class BodyReader {
 public:
  BodyReader(const ply::Header& header, const Element& vertex, const Element& face, const std::string& source)
      : header_(header),
        vertex_(vertex),
        face_(face),
        source_(source),
        vertex_plan_(plan_vertices(vertex, source)),
        face_list_(plan_faces(face, source)) {}

  Mesh read(Reader in, std::size_t body_bytes) {
    mesh_.positions.reserve(vertex_.count);
    if (vertex_plan_.normals) mesh_.normals.reserve(vertex_.count);
    if (vertex_plan_.colors) mesh_.colors.reserve(vertex_.count);
    if (vertex_plan_.uvs) mesh_.uvs.reserve(vertex_.count);
    if (vertex_plan_.intensities) mesh_.intensities.reserve(vertex_.count);
    reserve_triangles(body_bytes);
    // Faces need the vertices' positions to triangulate; PLY allows them first, so they may be read after.
    std::optional<Reader> faces_at;
    for (const Element& e : header_.elements) {
      if (&e == &vertex_) {
        for_each_entry(in, e, source_, [&] { push_vertex(vertex_values(in)); });
      } else if (&e == &face_ && mesh_.positions.size() == vertex_.count) {
        for_each_entry(in, e, source_, [&] { read_face(in, mesh_, faces_, polygon_, dropped_); });
      } else {
        if (&e == &face_) faces_at = in;
        for_each_entry(in, e, source_, [&] {
          for (const Property& p : e.properties) in.skip(p);
        });
      }
    }
    if (const std::string extra = in.trailing(); !extra.empty()) warn(source_, "ignored " + extra);
    if (faces_at)
      for_each_entry(*faces_at, face_, source_, [&] { read_face(*faces_at, mesh_, faces_, polygon_, dropped_); });
    return finish();
  }

  // An ASCII body of one entry per line, the vertices' lines and then the faces', read in two halves on two threads:
  // the vertices, then the faces (whose polygons need every position to triangulate). Empty when the body is not of
  // that shape or anything in it is wrong; read() then reads it again on one thread and reports the problem where it
  // is, so the mesh, warnings and errors are the same either way.
  std::optional<Mesh> read_by_lines(const char* body, const char* end) {
    if (header_.elements.size() != 2 || &header_.elements[0] != &vertex_) return std::nullopt;
    const std::uint64_t vertices = vertex_.count, faces = face_.count;
    // The second thread finds where its half begins by counting line breaks while the first parses.
    const char* faces_begin = nullptr;
    try {
      mesh_.positions.resize(vertices);
      if (vertex_plan_.normals) mesh_.normals.resize(vertices);
      if (vertex_plan_.colors) mesh_.colors.resize(vertices);
      if (vertex_plan_.uvs) mesh_.uvs.resize(vertices);
      if (vertex_plan_.intensities) mesh_.intensities.resize(vertices);
      if (!in_two(
              [&] {
                const char* p = body;
                return vertex_lines(p, end, 0, vertices / 2);
              },
              [&] {
                const char* p = after_lines(body, end, vertices / 2);
                if (!p || !vertex_lines(p, end, vertices / 2, vertices - vertices / 2)) return false;
                faces_begin = p;
                return true;
              }))
        return start_over();
      reserve_triangles(static_cast<std::size_t>(end - faces_begin));
      Mesh second;  // the second half's triangles and face numbers
      second.indices.reserve(mesh_.indices.capacity() / 2 + 3);
      FaceNumbering second_faces;
      std::vector<std::uint32_t> second_polygon;
      std::size_t second_dropped = 0;
      const bool read = in_two(
          [&] {
            const char* p = faces_begin;
            return each_line(p, end, faces / 2,
                             [&](AsciiReader& in) { read_face(in, mesh_, faces_, polygon_, dropped_); });
          },
          [&] {
            const char* p = after_lines(faces_begin, end, faces / 2);
            return p &&
                   each_line(
                       p, end, faces - faces / 2,
                       [&](AsciiReader& in) { read_face(in, second, second_faces, second_polygon, second_dropped); }) &&
                   AsciiReader(p, end, 0).exhausted();
          });
      if (!read) return start_over();
      append_faces(second, faces / 2);
      dropped_ += second_dropped;
    } catch (...) {
      return start_over();
    }
    return finish();
  }

 private:
  // A face's count and indices may be one byte each, so the count alone does not bound the triangles' memory.
  void reserve_triangles(std::size_t body_bytes) {
    std::uint64_t triangle_bytes = 3 * Reader::least_bytes(face_.properties[face_list_].type);
    for (const Property& p : face_.properties) triangle_bytes += Reader::least_bytes(p.list ? p.count_type : p.type);
    mesh_.indices.reserve(3 * std::min<std::uint64_t>(face_.count, body_bytes / triangle_bytes));
  }

  Mesh finish() {
    if (dropped_ > 0) warn(source_, "dropped " + std::to_string(dropped_) + " face(s) with fewer than 3 corners");
    return std::move(mesh_);
  }

  std::optional<Mesh> start_over() {
    mesh_ = Mesh();
    faces_ = FaceNumbering();
    dropped_ = 0;
    return std::nullopt;
  }

  // Where line k (from 0) begins, after k line breaks; null if the text has fewer. Counts line breaks a block at a
  // time (vectorised), then finds the last block's with memchr.
  static const char* after_lines(const char* p, const char* end, std::uint64_t k) {
    constexpr std::size_t kBlock = std::size_t{1} << 16;
    while (k > 0) {
      const std::size_t n = std::min<std::size_t>(kBlock, static_cast<std::size_t>(end - p));
      if (n == 0) return nullptr;
      const auto breaks = static_cast<std::uint64_t>(std::count(p, p + n, '\n'));
      if (breaks < k) {
        k -= breaks;
        p += n;
        continue;
      }
      for (;; --k) {
        p = static_cast<const char*>(std::memchr(p, '\n', static_cast<std::size_t>(end - p))) + 1;
        if (k == 1) return p;
      }
    }
    return p;
  }

  // Reads `count` lines from p, each with read_one over a reader of that line alone, moving p past them. False
  // unless every line holds exactly one entry (and throws what read_one throws).
  template <class ReadOne>
  static bool each_line(const char*& p, const char* end, std::uint64_t count, ReadOne&& read_one) {
    for (std::uint64_t i = 0; i < count; ++i) {
      if (p == end) return false;
      const auto* line_end = static_cast<const char*>(std::memchr(p, '\n', static_cast<std::size_t>(end - p)));
      if (!line_end) line_end = end;
      AsciiReader in(p, line_end, 0);
      read_one(in);
      if (!in.exhausted()) return false;
      p = line_end == end ? end : line_end + 1;
    }
    return true;
  }

  // Reads vertices first .. first + count - 1, one per line from p, moving p past them.
  bool vertex_lines(const char*& p, const char* end, std::uint64_t first, std::uint64_t count) {
    return each_line(p, end, count, [&](AsciiReader& in) { store_vertex(first++, vertex_values(in)); });
  }

  // Runs first here and second on another thread (or after first, when no thread can be started); true if both
  // returned true. Whatever either throws counts as false.
  template <class First, class Second>
  static bool in_two(First&& first, Second&& second) {
    const auto guarded = [](auto& task) {
      try {
        return task();
      } catch (...) {
        return false;
      }
    };
    bool second_ok = false;
    std::thread other;
    try {
      other = std::thread([&] { second_ok = guarded(second); });
    } catch (const std::system_error&) {
      return guarded(first) && guarded(second);
    }
    const bool first_ok = guarded(first);
    other.join();
    return first_ok && second_ok;
  }

  using Values = std::array<float, kRoleCount>;

  Values vertex_values(Reader& in) {
    Values v = {0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0};
    for (std::size_t j = 0; j < vertex_.properties.size(); ++j) {
      const Property& p = vertex_.properties[j];
      const Role role = vertex_plan_.roles[j];
      if (role == kSkip) {
        in.skip(p);
        continue;
      }
      const float value = narrow(in.scalar(p.type) / vertex_plan_.divisors[j]);
      if (!std::isfinite(value)) throw Problem{"non-finite value of " + in_quotes(p.name)};
      v[role] = value;
    }
    return v;
  }

  void push_vertex(const Values& v) {
    mesh_.positions.push_back({v[kX], v[kY], v[kZ]});
    if (vertex_plan_.normals) mesh_.normals.push_back({v[kNx], v[kNy], v[kNz]});
    if (vertex_plan_.colors) mesh_.colors.push_back({v[kRed], v[kGreen], v[kBlue], v[kAlpha]});
    if (vertex_plan_.uvs) mesh_.uvs.push_back({v[kU], v[kV]});
    if (vertex_plan_.intensities) mesh_.intensities.push_back(v[kIntensity]);
  }

  void store_vertex(std::uint64_t i, const Values& v) {
    mesh_.positions[i] = {v[kX], v[kY], v[kZ]};
    if (vertex_plan_.normals) mesh_.normals[i] = {v[kNx], v[kNy], v[kNz]};
    if (vertex_plan_.colors) mesh_.colors[i] = {v[kRed], v[kGreen], v[kBlue], v[kAlpha]};
    if (vertex_plan_.uvs) mesh_.uvs[i] = {v[kU], v[kV]};
    if (vertex_plan_.intensities) mesh_.intensities[i] = v[kIntensity];
  }

  // Appends a face's triangles to out.indices (and its number to numbering); polygon is scratch. Positions come
  // from mesh_, complete by now.
  void read_face(Reader& in, Mesh& out, FaceNumbering& numbering, std::vector<std::uint32_t>& polygon,
                 std::size_t& dropped) {
    polygon.clear();
    for (std::size_t j = 0; j < face_.properties.size(); ++j) {
      const Property& p = face_.properties[j];
      if (j != face_list_) {
        in.skip(p);
        continue;
      }
      const std::int64_t n = in.count(p.count_type);
      if (!in.fits(n, p.type))
        throw Problem{"a list of " + std::to_string(n) + " vertex indices runs past the end of the file"};
      if (n > kMaxCorners)
        throw Problem{"has " + std::to_string(n) + " corners, more than the " + std::to_string(kMaxCorners) +
                      " supported"};
      for (std::int64_t k = 0; k < n; ++k) {
        const std::int64_t index = in.integer(p.type);
        if (index < 0 || static_cast<std::uint64_t>(index) >= vertex_.count)
          throw Problem{"references vertex " + std::to_string(index) + " but there are only " +
                        std::to_string(vertex_.count) + " vertices"};
        polygon.push_back(static_cast<std::uint32_t>(index));
      }
    }
    const std::size_t before = out.indices.size() / 3;
    if (polygon.size() < 3) {
      ++dropped;
      numbering.drop_face();
      return;
    }
    if (polygon.size() == 3) {
      out.indices.insert(out.indices.end(), polygon.begin(), polygon.end());
    } else {
      triangulate_polygon(mesh_.positions, polygon, out.indices);
    }
    numbering.add_face(out, before);
  }

  // Appends the triangles and face numbers read from the second half of the faces, which begins at face `first`.
  void append_faces(Mesh& second, std::uint64_t first) {
    if (!mesh_.face_ids.empty() || !second.face_ids.empty()) {
      // An empty list numbers each triangle as its own face.
      for (Mesh* part : {&mesh_, &second}) {
        if (!part->face_ids.empty()) continue;
        part->face_ids.resize(part->indices.size() / 3);
        for (std::size_t t = 0; t < part->face_ids.size(); ++t) part->face_ids[t] = static_cast<std::uint32_t>(t);
      }
      for (std::uint32_t id : second.face_ids) mesh_.face_ids.push_back(static_cast<std::uint32_t>(id + first));
    }
    mesh_.indices.insert(mesh_.indices.end(), second.indices.begin(), second.indices.end());
  }

  const ply::Header& header_;
  const Element& vertex_;
  const Element& face_;
  const std::string& source_;
  VertexPlan vertex_plan_;
  std::size_t face_list_;
  FaceNumbering faces_;
  Mesh mesh_;
  std::vector<std::uint32_t> polygon_;  // reused for every face
  std::size_t dropped_ = 0;
};

// The elements' properties are checked before their counts, so that a malformed header says what is wrong with it
// rather than that its data is missing.
template <class Reader>
Mesh read_body(const ply::Header& header, const Element& vertex, const Element& face, std::size_t file_bytes, Reader in,
               const std::string& source, std::string_view by_lines = {}, bool* in_two = nullptr) {
  BodyReader<Reader> reader(header, vertex, face, source);
  const std::size_t body_bytes = file_bytes - header.body_offset;
  ply::check_counts(header, body_bytes, source);
  if constexpr (std::is_same_v<Reader, AsciiReader>) {
    if (!by_lines.empty()) {
      if (std::optional<Mesh> mesh = reader.read_by_lines(by_lines.data(), by_lines.data() + by_lines.size())) {
        if (in_two) *in_two = true;
        return std::move(*mesh);
      }
    }
  }
  return reader.read(in, body_bytes);
}

const Element* find(const ply::Header& header, std::string_view name) {
  for (const Element& e : header.elements)
    if (e.name == name) return &e;
  return nullptr;
}

}  // namespace

Mesh load_ply(std::string_view bytes, const std::string& source, int threads, std::size_t two_from, bool* in_two) {
  if (in_two) *in_two = false;
  const ply::Header header = ply::parse_header(bytes, source);
  const Element* vertex = find(header, "vertex");
  const Element* face = find(header, "face");
  if (!vertex) throw InputError(source, "PLY file has no 'vertex' element");
  if ((!face || face->count == 0) && is_splat_layout(*vertex)) return load_splat_ply(bytes, header, *vertex, source);
  // Without faces the file is a point cloud: every vertex is a point. Its body is read against a face element of
  // no entries, which takes no bytes.
  const Element no_faces{"face", 0, {ply::Property{"vertex_indices", ply::Type::kInt32, true, ply::Type::kUInt8}}};
  const bool cloud = !face || face->count == 0;
  if (cloud) {
    if (find(header, "tristrips")) throw InputError(source, "PLY triangle strips ('tristrips') are not supported");
    if (vertex->count == 0) throw InputError(source, "nothing to draw (no vertices and no faces)");
    if (!face) face = &no_faces;
  }
  if (vertex->count > std::uint64_t{UINT32_MAX})
    throw InputError(source, "too many vertices for 32-bit indices (" + std::to_string(vertex->count) + ")");

  const char* begin = bytes.data();
  const char* body = begin + header.body_offset;
  const char* end = begin + bytes.size();
  Mesh mesh;
  using ply::Encoding;
  if (header.encoding == Encoding::kAscii) {
    if (threads == 0) threads = static_cast<int>(std::thread::hardware_concurrency());
    const bool by_lines = threads > 1 && static_cast<std::size_t>(end - body) >= two_from;
    mesh =
        read_body(header, *vertex, *face, bytes.size(), AsciiReader(body, end, header.body_line), source,
                  by_lines ? std::string_view(body, static_cast<std::size_t>(end - body)) : std::string_view(), in_two);
  } else if ((header.encoding == Encoding::kBinaryLittleEndian) == detail::kLittleEndian) {
    mesh = read_body(header, *vertex, *face, bytes.size(), BinaryReader<false>(begin, body, end), source);
  } else {
    mesh = read_body(header, *vertex, *face, bytes.size(), BinaryReader<true>(begin, body, end), source);
  }
  if (cloud) {
    mesh.points_at_every_vertex();
  } else if (mesh.indices.empty()) {
    throw InputError(source, "no triangles found");
  }
  validate(mesh, source);
  return mesh;
}

}  // namespace facet
