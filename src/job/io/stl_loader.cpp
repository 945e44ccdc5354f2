// stl_loader.cpp - load_stl(): binary and ASCII STL, facets kept in order, equal positions welded into shared vertices.
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "facet/detail/bits.hpp"
#include "facet/error.hpp"
#include "job/io/loaders.hpp"
#include "job/io/text_scan.hpp"

namespace facet {
namespace {

constexpr std::size_t kHeaderBytes = 84;  // 80 free bytes, then the uint32 triangle count
constexpr std::size_t kFacetBytes = 50;   // normal, 3 corners (12 floats), uint16 attribute

bool finite(const glm::vec3& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z); }

// STL lists every corner of every facet; edges and outlines need corners at one position to be one vertex. An
// open-addressing table of vertex numbers keyed by the position's bits (at most half full, so probes stay short);
// each slot holds the key's hash in its upper half, so most mismatches are settled without reading the position.
class Welder {
 public:
  Welder(std::vector<glm::vec3>& positions, std::size_t expected_vertices) : positions_(positions) {
    std::size_t capacity = 64;
    while (capacity < 2 * expected_vertices) capacity *= 2;
    slots_.assign(capacity, 0);
    positions_.reserve(expected_vertices);
  }

  std::uint32_t add(glm::vec3 p) {
    p += glm::vec3(0.0f);  // turns -0 into +0 (and changes nothing else), so that the two zeros weld together
    const std::uint64_t h = hash(p);
    const std::uint64_t tag = h & ~std::uint64_t{0xffffffff};
    for (std::size_t i = h & mask();; i = (i + 1) & mask()) {
      const std::uint64_t slot = slots_[i];
      if (slot == 0) {
        if (2 * (positions_.size() + 1) > slots_.size()) {
          grow();
          return add(p);
        }
        const auto index = static_cast<std::uint32_t>(positions_.size());
        positions_.push_back(p);
        slots_[i] = tag | (std::uint64_t{index} + 1);
        return index;
      }
      if ((slot & ~std::uint64_t{0xffffffff}) == tag) {
        const std::uint32_t index = static_cast<std::uint32_t>(slot) - 1;
        if (std::memcmp(&positions_[index], &p, sizeof p) == 0) return index;
      }
    }
  }

  // Where the search for p starts, for weld() to prefetch. (A member function that only prefetched would be
  // deleted: GCC deems it free of side effects.)
  const std::uint64_t* first_slot(const glm::vec3& p) const { return &slots_[hash(p + glm::vec3(0.0f)) & mask()]; }

 private:
  static std::uint64_t hash(const glm::vec3& p) {
    std::uint64_t h =
        (std::uint64_t{detail::bit_cast<std::uint32_t>(p.x)} << 32 | detail::bit_cast<std::uint32_t>(p.y)) *
        0x9e3779b97f4a7c15ull;
    h ^= (h >> 29) + std::uint64_t{detail::bit_cast<std::uint32_t>(p.z)} * 0xc2b2ae3d27d4eb4full;
    h *= 0xd6e8feb86659fd93ull;
    return h ^ (h >> 32);
  }
  std::size_t mask() const { return slots_.size() - 1; }

  void grow() {
    slots_.assign(2 * slots_.size(), 0);
    for (std::size_t v = 0; v < positions_.size(); ++v) {
      const std::uint64_t h = hash(positions_[v]);
      std::size_t i = h & mask();
      while (slots_[i] != 0) i = (i + 1) & mask();
      slots_[i] = (h & ~std::uint64_t{0xffffffff}) | (std::uint64_t{v} + 1);
    }
  }

  std::vector<glm::vec3>& positions_;
  std::vector<std::uint64_t> slots_;
};

std::uint32_t read_u32_le(const char* p) {
  std::uint32_t v;
  std::memcpy(&v, p, sizeof v);
  if constexpr (!detail::kLittleEndian) v = __builtin_bswap32(v);
  return v;
}

glm::vec3 read_corner(const char* p) {
  return {detail::bit_cast<float>(read_u32_le(p)), detail::bit_cast<float>(read_u32_le(p + 4)),
          detail::bit_cast<float>(read_u32_le(p + 8))};
}

// Welds corners 0 .. n-1 (three per facet, in order) into mesh.positions and mesh.indices. The corners are all known
// before welding starts, so the table's slots for a corner a few facets ahead are fetched while this one is looked
// up: that hides the table's cache misses (binary 2 M facets: 238 -> 384 MB/s). non_finite(c) is called for a
// corner that is not finite: the binary reader throws there (ASCII corners are checked as they are read).
template <class Corner, class NonFinite>
void weld(std::size_t n, Corner&& corner, NonFinite&& non_finite, Mesh& mesh) {
  constexpr std::size_t kAhead = 24;
  mesh.indices.resize(n);
  // Closed meshes have about half as many vertices as facets; the table grows if there are more.
  Welder welder(mesh.positions, n / 6 + 3);
  for (std::size_t c = 0; c < n; ++c) {
    if (c + kAhead < n) __builtin_prefetch(welder.first_slot(corner(c + kAhead)));
    const glm::vec3 p = corner(c);
    if (!finite(p)) non_finite(c);
    mesh.indices[c] = welder.add(p);
  }
}

Mesh load_binary(std::string_view bytes, const std::string& source) {
  const std::size_t count = read_u32_le(bytes.data() + 80);
  if (count == 0) throw InputError(source, "no triangles found (binary STL with a triangle count of 0)");
  const char* facets = bytes.data() + kHeaderBytes;
  const auto at = [&](std::size_t c) { return facets + c / 3 * kFacetBytes + 12 + 12 * (c % 3); };
  Mesh mesh;
  weld(
      3 * count, [&](std::size_t c) { return read_corner(at(c)); },
      [&](std::size_t c) {
        throw InputError(source, "non-finite vertex position in triangle " + std::to_string(c / 3) + " (byte offset " +
                                     std::to_string(at(c) - bytes.data()) + ")");
      },
      mesh);
  return mesh;
}

bool keyword(std::string_view token, std::string_view word) {
  if (token.size() != word.size()) return false;
  for (std::size_t i = 0; i < word.size(); ++i)
    if ((token[i] | 0x20) != word[i]) return false;  // ASCII letters in either case ("SOLID", "Facet")
  return true;
}

// ASCII STL: any number of "solid [name] facet normal n n n outer loop vertex x y z (3 times) endloop endfacet ...
// endsolid [name]" blocks, keywords in any case, tokens separated by any whitespace.
class AsciiReader {
 public:
  AsciiReader(std::string_view text, const std::string& source)
      : in_(text.data(), text.data() + text.size(), 1), source_(source) {}

  Mesh read() {
    std::vector<glm::vec3> corners;  // welded once all are read, as in binary files
    for (std::string_view token = in_.next(); !token.empty(); token = in_.next()) {
      if (!keyword(token, "solid")) fail("expected 'solid'", token);
      in_.skip_line();
      for (token = in_.next(); !keyword(token, "endsolid"); token = in_.next()) {
        if (token.empty()) throw InputError(source_, "file ends inside a solid (no 'endsolid')");
        if (!keyword(token, "facet")) fail("expected 'facet' or 'endsolid'", token);
        expect("normal");
        for (int k = 0; k < 3; ++k) number();  // the renderer computes its own normals
        expect("outer");
        expect("loop");
        for (int k = 0; k < 3; ++k) {
          expect("vertex");
          const glm::vec3 p{number(), number(), number()};  // braces: read left to right
          if (!finite(p)) throw InputError(source_, "non-finite vertex position on line " + std::to_string(in_.line()));
          corners.push_back(p);
        }
        expect("endloop");
        expect("endfacet");
      }
      in_.skip_line();
    }
    if (corners.empty()) throw InputError(source_, "no triangles found (ASCII STL without facets)");
    Mesh mesh;
    weld(
        corners.size(), [&](std::size_t c) { return corners[c]; }, [](std::size_t) {}, mesh);
    return mesh;
  }

 private:
  [[noreturn]] void fail(const std::string& what, std::string_view token) const {
    if (token.empty()) throw InputError(source_, what + " but the file ends");
    throw InputError(source_, what + " on line " + std::to_string(in_.line()) + ", found " + in_quotes(token));
  }

  void expect(std::string_view word) {
    const std::string_view token = in_.next();
    if (!keyword(token, word)) fail("expected '" + std::string(word) + "'", token);
  }

  float number() {
    const std::string_view token = in_.next();
    float value;
    if (token.empty() || !parse_real(token, value)) fail("expected a number", token);
    return value;
  }

  TextCursor in_;
  const std::string& source_;
};

bool starts_with_solid(std::string_view bytes) {
  std::size_t i = 0;
  while (i < bytes.size() && is_space(bytes[i])) ++i;
  return keyword(bytes.substr(i, 5), "solid") && (i + 5 == bytes.size() || is_space(bytes[i + 5]));
}

}  // namespace

bool is_binary_stl(std::string_view bytes) {
  return bytes.size() >= kHeaderBytes &&
         (bytes.size() - kHeaderBytes) / kFacetBytes == read_u32_le(bytes.data() + 80) &&
         (bytes.size() - kHeaderBytes) % kFacetBytes == 0;
}

Mesh load_stl(std::string_view bytes, const std::string& source) {
  // ASCII STL has no NUL bytes; binary facets nearly always do (a 0.0 coordinate, the attribute word), so a cut
  // binary file whose header begins with "solid" is still reported as a binary one.
  const bool text = bytes.substr(0, 1024).find('\0') == std::string_view::npos;
  Mesh mesh;
  if (is_binary_stl(bytes)) {
    mesh = load_binary(bytes, source);
  } else if (text && starts_with_solid(bytes)) {
    mesh = AsciiReader(bytes, source).read();
  } else if (bytes.size() < kHeaderBytes) {
    throw InputError(source, "not an STL file: " + std::to_string(bytes.size()) +
                                 " bytes is too short for a binary STL (84 or more) and there is no 'solid' keyword");
  } else {
    const std::uint64_t claimed = read_u32_le(bytes.data() + 80);
    throw InputError(source, "binary STL header claims " + std::to_string(claimed) + " triangles (" +
                                 std::to_string(kHeaderBytes + kFacetBytes * claimed) + " bytes) but the file has " +
                                 std::to_string(bytes.size()) + " bytes (truncated?)");
  }
  validate(mesh, source);
  return mesh;
}

}  // namespace facet
