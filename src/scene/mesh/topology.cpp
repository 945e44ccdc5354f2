// topology.cpp - connectivity work on meshes: edges, smooth and crease normals, strips, fans, polygon triangulation.
#include <algorithm>
#include <cmath>
#include <limits>
#include <span>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <unordered_map>
#include <utility>

#include "facet/detail/bits.hpp"
#include "facet/detail/default_init.hpp"
#include "facet/error.hpp"
#include "facet/framebuffer.hpp"
#include "facet/mesh.hpp"

namespace facet {

namespace {

using Edge = std::array<std::uint32_t, 2>;

void sort_unique(std::vector<Edge>& edges) {
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
}

void add_edge(std::vector<Edge>& edges, std::uint32_t a, std::uint32_t b) {
  if (a != b) edges.push_back({std::min(a, b), std::max(a, b)});
}

// Positions compare by value, as the benchmark's reference renderer does (BENCHMARK.md 8.3), so -0 and +0 are one key.
struct PositionKey {
  std::uint32_t bits[3];
  explicit PositionKey(const glm::vec3& p) {
    for (int k = 0; k < 3; ++k) bits[k] = detail::bit_cast<std::uint32_t>(p[k] == 0.0f ? 0.0f : p[k]);
  }
  bool operator==(const PositionKey& o) const {
    return bits[0] == o.bits[0] && bits[1] == o.bits[1] && bits[2] == o.bits[2];
  }
};

std::uint64_t position_hash(const PositionKey& k) {
  std::uint64_t h = 0x9e3779b97f4a7c15ull;
  for (std::uint32_t b : k.bits) h = (h ^ b) * 0x100000001b3ull;
  return h ^ (h >> 29);
}

struct PositionKeyHash {
  std::size_t operator()(const PositionKey& k) const { return static_cast<std::size_t>(position_hash(k)); }
};

bool has_repeat(std::uint32_t a, std::uint32_t b, std::uint32_t c) { return a == b || b == c || a == c; }

}  // namespace

std::vector<Edge> unique_edges(const Mesh& mesh) {
  std::vector<Edge> edges;
  edges.reserve(mesh.indices.size());
  for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    const std::uint32_t a = mesh.indices[t], b = mesh.indices[t + 1], c = mesh.indices[t + 2];
    add_edge(edges, a, b);
    add_edge(edges, b, c);
    add_edge(edges, c, a);
  }
  sort_unique(edges);
  return edges;
}

std::vector<Edge> unique_edges(const PolygonMesh& polygons) {
  std::vector<Edge> edges;
  for (const auto& poly : polygons.polygons)
    for (std::size_t i = 0; i < poly.size() && poly.size() >= 2; ++i)
      add_edge(edges, poly[i], poly[(i + 1) % poly.size()]);
  sort_unique(edges);
  return edges;
}

void compute_smooth_normals(Mesh& mesh) {
  const std::size_t n = mesh.positions.size();
  std::vector<std::uint32_t> group(n);
  std::unordered_map<PositionKey, std::uint32_t, PositionKeyHash> groups;
  groups.reserve(n);
  for (std::size_t v = 0; v < n; ++v)
    group[v] =
        groups.try_emplace(PositionKey(mesh.positions[v]), static_cast<std::uint32_t>(groups.size())).first->second;
  // Float sums in triangle order, like the reference renderer, so both produce the same bits.
  std::vector<glm::vec3> sum(groups.size(), glm::vec3(0));
  for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    const std::uint32_t i0 = mesh.indices[t], i1 = mesh.indices[t + 1], i2 = mesh.indices[t + 2];
    if (i0 >= n || i1 >= n || i2 >= n) continue;
    const glm::vec3 e1 = mesh.positions[i1] - mesh.positions[i0];
    const glm::vec3 e2 = mesh.positions[i2] - mesh.positions[i0];
    const glm::vec3 face(e1.y * e2.z - e1.z * e2.y, e1.z * e2.x - e1.x * e2.z, e1.x * e2.y - e1.y * e2.x);
    for (std::uint32_t i : {i0, i1, i2}) sum[group[i]] += face;
  }
  mesh.normals.resize(n);
  for (std::size_t v = 0; v < n; ++v) {
    const glm::vec3 s = sum[group[v]];
    const float len = std::sqrt(s.x * s.x + s.y * s.y + s.z * s.z);
    mesh.normals[v] = len > 0 ? s / len : glm::vec3(0, 0, 1);  // also catches a NaN length
  }
}

namespace {

using NormalBits = std::array<std::uint32_t, 3>;

// The crease normals' large temporaries (tens of MB for a million triangles) are written once, right after
// allocation: on huge pages (CacheAlignedAllocator) that costs one fault per 2 MiB rather than one per 4 KiB. Their
// elements are default-initialised (left unset, for these types) rather than zeroed: each is written before it is
// read, and zeroing first would write every byte twice (a memset was 18% of an 870k-triangle PLY's render).
template <class T>
using Scratch = std::vector<T, detail::DefaultInitAllocator<CacheAlignedAllocator<T>>>;

NormalBits bits_of(const glm::vec3& v) {
  return {detail::bit_cast<std::uint32_t>(v.x), detail::bit_cast<std::uint32_t>(v.y),
          detail::bit_cast<std::uint32_t>(v.z)};
}

// The same grouping as compute_smooth_normals (kept separate so that function stays exactly as the reference
// renderer's): group[v] is the index of v's position among the distinct positions. Returns the number of groups.
// Groups are numbered in order of first appearance. The table is open addressing over a power of two of at least
// twice the vertices, each slot holding a group's first vertex + 1 (0: empty) beside the top bits of its hash, so a
// probe meets a different position's slot without reading that position. The table is megabytes for a large mesh and
// each lookup lands at random in it: slots are prefetched a few vertices ahead, which halves the time here.
std::size_t group_by_position(const std::vector<glm::vec3>& positions, Scratch<std::uint32_t>& group) {
  const std::size_t n = positions.size();
  if (n >= 0xffffffffu)
    throw std::length_error("compute_crease_normals: more vertices than 32-bit indices can address");
  std::size_t capacity = 16;
  while (capacity < 2 * n) capacity *= 2;
  struct Slot {
    std::uint32_t vertex_plus_one, tag;
  };
  Scratch<Slot> slots(capacity, Slot{0, 0});
  group.resize(n);
  const auto hash_of = [&](std::size_t v) { return position_hash(PositionKey(positions[v])); };
  constexpr std::size_t kAhead = 16;
  std::uint32_t groups = 0;
  for (std::size_t v = 0; v < n; ++v) {
    if (v + kAhead < n) __builtin_prefetch(&slots[hash_of(v + kAhead) & (capacity - 1)]);
    const PositionKey key(positions[v]);
    const std::uint64_t hash = position_hash(key);
    const auto tag = static_cast<std::uint32_t>(hash >> 32);
    for (std::size_t s = hash & (capacity - 1);; s = (s + 1) & (capacity - 1)) {
      const Slot held = slots[s];
      if (held.vertex_plus_one == 0) {
        slots[s] = {static_cast<std::uint32_t>(v + 1), tag};
        group[v] = groups++;
        break;
      }
      if (held.tag == tag && PositionKey(positions[held.vertex_plus_one - 1]) == key) {
        group[v] = group[held.vertex_plus_one - 1];
        break;
      }
    }
  }
  return groups;
}

// s / |s| with the arithmetic of compute_smooth_normals, or fallback when s has no direction (zero, or so large that
// its length overflowed).
glm::vec3 normalized_or(const glm::vec3& s, const glm::vec3& fallback) {
  const float len = std::sqrt(s.x * s.x + s.y * s.y + s.z * s.z);
  return len > 0 && std::isfinite(len) ? s / len : fallback;
}

// A triangle corner, 3 t + k: 32 bits (checked) rather than size_t, as the several per-corner arrays dominate the
// memory this takes.
using Corner = std::uint32_t;

// The corners of the usable triangles in order, as a range bucket() can walk without storing them: 0 .. 3 t - 1 but
// for the corners of the triangles listed (in order) in `skipped`. A mesh with a few degenerate triangles (a UV
// sphere's poles) would otherwise need its ten-megabyte list of corners.
struct UsableCorners {
  struct Iterator {
    Corner c;
    const std::size_t* skip;  // the next unusable triangle at or after c's
    const std::size_t* skip_end;
    Corner operator*() const { return c; }
    Iterator& operator++() {
      ++c;
      if (c % 3 == 0) settle();
      return *this;
    }
    // Moves c past any unusable triangles starting at it.
    void settle() {
      while (skip != skip_end && *skip == c / 3) {
        c += 3;
        ++skip;
      }
    }
    bool operator!=(const Iterator& other) const { return c != other.c; }
  };
  std::span<const std::size_t> skipped;
  Corner count;  // all corners, 3 t
  Iterator begin() const {
    Iterator it{0, skipped.data(), skipped.data() + skipped.size()};
    it.settle();
    return it;
  }
  Iterator end() const { return {count, nullptr, nullptr}; }
  std::size_t size() const { return count - 3 * skipped.size(); }
};

// Counting sort of items by key (key(item) < buckets): start gets buckets + 1 offsets, sorted the items bucket by
// bucket, each bucket keeping the items' order. Linear, and reuses the vectors' storage when called again.
template <typename Items, typename Key>
void bucket(const Items& items, std::size_t buckets, Scratch<Corner>& start, Scratch<Corner>& sorted, Key key) {
  start.assign(buckets + 1, 0);
  for (Corner item : items) ++start[key(item) + 1];
  for (std::size_t b = 0; b < buckets; ++b) start[b + 1] += start[b];
  sorted.resize(items.size());
  for (Corner item : items) sorted[start[key(item)]++] = item;
  // Each start[b] has moved on to the end of bucket b, which is where bucket b + 1 begins: shift them back.
  for (std::size_t b = buckets; b > 0; --b) start[b] = start[b - 1];
  start[0] = 0;
}

}  // namespace

void compute_crease_normals(Mesh& mesh, float crease_angle_radians) {
  const std::size_t n = mesh.positions.size();
  const std::size_t triangles = mesh.indices.size() / 3;
  if (mesh.indices.size() > std::numeric_limits<Corner>::max())
    throw std::length_error("compute_crease_normals: more indices than 32-bit corner numbers can address");
  Scratch<std::uint32_t> group;
  const std::size_t group_count = group_by_position(mesh.positions, group);

  // Per triangle, the unnormalised face normal (twice the area long: the weight, computed as in
  // compute_smooth_normals so a 180 degree crease reproduces it bit for bit). The unit normal for the angle test is
  // computed from it where a group needs it (unit_of): stored, it would be ten more megabytes a million triangles.
  // Triangles with an index out of range, zero area or a non-finite normal are unusable: they add nothing and keep
  // their indices, so a degenerate triangle can neither split a vertex nor make a NaN.
  Scratch<glm::vec3> area(triangles);
  Scratch<Corner> start, bucketed;    // counting sorts' output (bucket), reused
  std::vector<std::size_t> unusable;  // in order; usually none
  for (std::size_t t = 0; t < triangles; ++t) {
    const std::uint32_t i0 = mesh.indices[3 * t], i1 = mesh.indices[3 * t + 1], i2 = mesh.indices[3 * t + 2];
    if (i0 >= n || i1 >= n || i2 >= n) {
      unusable.push_back(t);
      continue;
    }
    const glm::vec3 e1 = mesh.positions[i1] - mesh.positions[i0];
    const glm::vec3 e2 = mesh.positions[i2] - mesh.positions[i0];
    area[t] = glm::vec3(e1.y * e2.z - e1.z * e2.y, e1.z * e2.x - e1.x * e2.z, e1.x * e2.y - e1.y * e2.x);
    const float len = std::sqrt(glm::dot(area[t], area[t]));
    if (!(len > 0) || !std::isfinite(len)) unusable.push_back(t);
  }
  const auto unit_of = [&](Corner c) {
    const glm::vec3& a = area[c / 3];
    return a / std::sqrt(glm::dot(a, a));
  };
  const UsableCorners usable_corners{unusable, static_cast<Corner>(3 * triangles)};
  start.reserve(std::max(n, std::size_t{1}) + 1);  // room for both sorts' offsets (group_count <= n)

  // The crease test is dot(own, other) >= cos(angle). The 1e-6 of slack keeps faces that are coplanar (or exactly at
  // the crease angle) but differ by rounding together; at 180 degrees or more every face counts.
  const float pi = 3.14159265358979f;
  const float angle = crease_angle_radians > 0 ? std::min(crease_angle_radians, pi) : 0.0f;  // NaN counts as 0
  const bool everything = crease_angle_radians >= pi;
  const float min_dot = everything ? -std::numeric_limits<float>::infinity() : std::cos(angle) - 1e-6f;
  // If every face is within angle / 2 of one direction, any two are within angle of each other (triangle inequality
  // on the sphere), so each corner sums every face; the margin covers rounding in both tests.
  const float min_dot_to_mean = std::cos(angle / 2) + 1e-5f;

  // Corners by position group; counting sort, so each group lists its corners in triangle order.
  bucket(usable_corners, group_count, start, bucketed, [&](Corner c) { return group[mesh.indices[c]]; });
  std::size_t largest = 0;
  for (std::size_t g = 0; g < group_count; ++g) largest = std::max<std::size_t>(largest, start[g + 1] - start[g]);

  // Each corner's normal, as an index into `normals`: the groups' smooth normals first (the normal of nearly every
  // corner), then the normals of crease-split corners as they are found. Four bytes a corner rather than twelve.
  Scratch<std::uint32_t> corner_normal(mesh.indices.size());
  Scratch<glm::vec3> normals;
  normals.reserve(group_count + group_count / 8);
  normals.resize(group_count);
  // A creased group's unit face normals, one per member, and the members' places sorted by them; reused.
  std::vector<glm::vec3> member_unit;
  std::vector<std::uint32_t> by_normal;
  member_unit.reserve(largest);
  by_normal.reserve(largest);
  for (std::size_t g = 0; g < group_count; ++g) {
    const std::span<const Corner> members(bucketed.data() + start[g], bucketed.data() + start[g + 1]);
    // The plain area-weighted sum over the group, in triangle order: the smooth normal. Every corner whose faces are
    // all within the crease angle gets exactly these bits, which is what keeps smooth regions' vertices shared.
    glm::vec3 sum(0);
    for (Corner c : members) sum += area[c / 3];
    normals[g] = normalized_or(sum, glm::vec3(0, 0, 1));
    if (members.empty()) continue;
    // If every face is within half the angle of the group's normal, every corner sees all of them: one sum for the
    // group, so high-valence smooth vertices (a sphere's poles) cost no more than at pi.
    // The test dot(unit, mean) >= min is done as dot(area, mean)^2 >= min^2 |area|^2 (min is positive), without
    // a square root or division per corner; the margin in min_dot_to_mean covers the different rounding.
    bool all_within = everything || glm::dot(sum, sum) > 0;
    const float min_squared = min_dot_to_mean * min_dot_to_mean;
    for (std::size_t i = 0; i < members.size() && all_within && !everything; ++i) {
      const glm::vec3& a = area[members[i] / 3];
      const float d = glm::dot(a, normals[g]);
      all_within = d > 0 && d * d >= min_squared * glm::dot(a, a);
    }
    if (all_within) {
      for (Corner c : members) corner_normal[c] = static_cast<std::uint32_t>(g);
      continue;
    }
    // Otherwise each distinct face normal sums the faces within the angle of it: O(distinct x members), where the
    // distinct normals are few except at the apex of a sharp cone-like fan.
    member_unit.clear();
    by_normal.clear();
    for (std::uint32_t i = 0; i < members.size(); ++i) {
      member_unit.push_back(unit_of(members[i]));
      by_normal.push_back(i);
    }
    const auto unit_bits = [&](std::uint32_t i) { return bits_of(member_unit[i]); };
    std::sort(by_normal.begin(), by_normal.end(),
              [&](std::uint32_t a, std::uint32_t b) { return unit_bits(a) < unit_bits(b); });
    for (std::size_t begin = 0, end = 0; begin < by_normal.size(); begin = end) {
      const glm::vec3 own = member_unit[by_normal[begin]];
      for (end = begin + 1; end < by_normal.size() && unit_bits(by_normal[end]) == bits_of(own);) ++end;
      // In triangle order, so corners that see the same set of faces get the same bits and share a vertex.
      glm::vec3 s(0);
      for (std::size_t i = 0; i < members.size(); ++i)
        if (glm::dot(own, member_unit[i]) >= min_dot) s += area[members[i] / 3];
      if (normals.size() >= std::numeric_limits<std::uint32_t>::max())
        throw std::length_error("compute_crease_normals: more normals than 32-bit indices can address");
      const auto id = static_cast<std::uint32_t>(normals.size());
      normals.push_back(normalized_or(s, own));
      for (std::size_t k = begin; k < end; ++k) corner_normal[members[by_normal[k]]] = id;
    }
  }

  // Corners by vertex, sorted by normal bits: each run of equal normals is one vertex. The first run keeps the
  // original index (so unsplit vertices, and edges listed by index, stay valid); each further run is a copy appended
  // after the original vertices.
  bucket(usable_corners, n, start, bucketed, [&](Corner c) { return mesh.indices[c]; });
  const auto bits = [&](Corner c) { return bits_of(normals[corner_normal[c]]); };
  const auto normal_less = [&](Corner a, Corner b) { return bits(a) < bits(b); };
  const auto same_normal = [&](Corner a, Corner b) {
    return corner_normal[a] == corner_normal[b] || bits(a) == bits(b);
  };
  std::size_t total = n;
  for (std::size_t v = 0; v < n; ++v) {
    Corner* const first = bucketed.data() + start[v];
    Corner* const last = bucketed.data() + start[v + 1];
    // Most vertices' corners all share one normal: nothing to sort or split there.
    if (std::all_of(first, last, [&](Corner c) { return corner_normal[c] == corner_normal[*first]; })) continue;
    std::sort(first, last, normal_less);
    for (Corner i = start[v] + 1; i < start[v + 1]; ++i) total += !same_normal(bucketed[i], bucketed[i - 1]);
  }
  if (std::uint64_t{total} > std::uint64_t{std::numeric_limits<std::uint32_t>::max()} + 1)
    throw std::length_error("compute_crease_normals: more vertices than 32-bit indices can address");

  // Attributes with one entry per vertex are copied along; a wrongly sized one is left alone (the mesh was already
  // invalid, and users check sizes against positions).
  const bool copy_uvs = mesh.uvs.size() == n, copy_uvs1 = mesh.uvs1.size() == n, copy_colors = mesh.colors.size() == n;
  mesh.positions.resize(total);
  mesh.normals.assign(total, glm::vec3(0, 0, 1));
  mesh.tangents.clear();  // made for the normals replaced here
  if (copy_uvs) mesh.uvs.resize(total);
  if (copy_uvs1) mesh.uvs1.resize(total);
  if (copy_colors) mesh.colors.resize(total);
  std::size_t next = n;
  for (std::size_t v = 0; v < n; ++v) {
    const Corner first = start[v], last = start[v + 1];
    // A vertex no usable triangle uses has no face of its own to compare with: it gets the smooth normal.
    if (first == last) mesh.normals[v] = normals[group[v]];
    for (Corner i = first; i < last; ++i) {
      const Corner c = bucketed[i];
      std::size_t target = v;
      if (i == first) {
        mesh.normals[v] = normals[corner_normal[c]];
      } else if (!same_normal(c, bucketed[i - 1])) {
        target = next++;
        mesh.positions[target] = mesh.positions[v];
        mesh.normals[target] = normals[corner_normal[c]];
        if (copy_uvs) mesh.uvs[target] = mesh.uvs[v];
        if (copy_uvs1) mesh.uvs1[target] = mesh.uvs1[v];
        if (copy_colors) mesh.colors[target] = mesh.colors[v];
      } else {
        target = mesh.indices[bucketed[i - 1]];  // same run as the previous corner, already re-pointed
      }
      mesh.indices[c] = static_cast<std::uint32_t>(target);
    }
  }
}

std::vector<std::uint32_t> triangles_from_strip(std::span<const std::uint32_t> strip) {
  std::vector<std::uint32_t> out;
  if (strip.size() < 3) return out;
  out.reserve(3 * (strip.size() - 2));
  for (std::size_t i = 0; i + 2 < strip.size(); ++i) {
    // Odd triangles are listed clockwise in the strip; swapping the first two restores counter-clockwise.
    const std::uint32_t a = (i % 2 == 0) ? strip[i] : strip[i + 1];
    const std::uint32_t b = (i % 2 == 0) ? strip[i + 1] : strip[i];
    const std::uint32_t c = strip[i + 2];
    if (has_repeat(a, b, c)) continue;
    out.insert(out.end(), {a, b, c});
  }
  return out;
}

std::vector<std::uint32_t> triangles_from_fan(std::span<const std::uint32_t> fan) {
  std::vector<std::uint32_t> out;
  if (fan.size() < 3) return out;
  out.reserve(3 * (fan.size() - 2));
  for (std::size_t i = 1; i + 1 < fan.size(); ++i) {
    if (has_repeat(fan[0], fan[i], fan[i + 1])) continue;
    out.insert(out.end(), {fan[0], fan[i], fan[i + 1]});
  }
  return out;
}

namespace {

double cross2(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c) {
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

// Inclusive of the edges, so a vertex touching a candidate ear blocks it (the safe choice).
bool inside_triangle(const glm::dvec2& p, const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c) {
  return cross2(a, b, p) >= 0 && cross2(b, c, p) >= 0 && cross2(c, a, p) >= 0;
}

void fan(std::span<const std::uint32_t> polygon, std::vector<std::uint32_t>& out) {
  for (std::size_t i = 1; i + 1 < polygon.size(); ++i) out.insert(out.end(), {polygon[0], polygon[i], polygon[i + 1]});
}

}  // namespace

void triangulate_polygon(std::span<const glm::vec3> positions, std::span<const std::uint32_t> polygon,
                         std::vector<std::uint32_t>& out) {
  const std::size_t n = polygon.size();
  if (n < 3) return;
  if (n == 3) return fan(polygon, out);

  // Newell's normal gives the polygon's plane and winding even when some corners are collinear or reflex.
  glm::dvec3 normal(0);
  for (std::size_t i = 0; i < n; ++i) {
    const glm::dvec3 a = positions[polygon[i]], b = positions[polygon[(i + 1) % n]];
    normal += glm::dvec3((a.y - b.y) * (a.z + b.z), (a.z - b.z) * (a.x + b.x), (a.x - b.x) * (a.y + b.y));
  }
  const glm::dvec3 mag = glm::abs(normal);
  if (!(mag.x + mag.y + mag.z > 0) || !std::isfinite(mag.x + mag.y + mag.z)) return fan(polygon, out);
  // Drop the dominant axis; the remaining two are ordered so the polygon winds counter-clockwise in 2D.
  int axis = 2;
  if (mag.x >= mag.y && mag.x >= mag.z) axis = 0;
  else if (mag.y >= mag.z) axis = 1;
  int u = (axis + 1) % 3, v = (axis + 2) % 3;  // cyclic, so (u, v, axis) is right-handed
  if (normal[axis] < 0) std::swap(u, v);
  std::vector<glm::dvec2> p(n);
  for (std::size_t i = 0; i < n; ++i) p[i] = {positions[polygon[i]][u], positions[polygon[i]][v]};

  bool convex = true;
  for (std::size_t i = 0; i < n && convex; ++i) convex = cross2(p[(i + n - 1) % n], p[i], p[(i + 1) % n]) >= 0;
  if (convex) return fan(polygon, out);

  // Ear clipping. The search resumes where the last ear was cut, so typical polygons take O(n^2); if a whole lap
  // finds no ear (self-intersecting or degenerate input) the remainder is fanned so the loop always ends.
  std::vector<std::size_t> rem(n);
  for (std::size_t i = 0; i < n; ++i) rem[i] = i;
  std::size_t k = 0, misses = 0;
  while (rem.size() > 3) {
    const std::size_t m = rem.size();
    if (misses >= m) break;
    k %= m;
    const std::size_t a = rem[(k + m - 1) % m], b = rem[k], c = rem[(k + 1) % m];
    bool ear = cross2(p[a], p[b], p[c]) > 0;
    for (std::size_t j = 0; j < m && ear; ++j) {
      const std::size_t o = rem[j];
      if (o == a || o == b || o == c || p[o] == p[a] || p[o] == p[b] || p[o] == p[c]) continue;
      ear = !inside_triangle(p[o], p[a], p[b], p[c]);
    }
    if (!ear) {
      ++k;
      ++misses;
      continue;
    }
    out.insert(out.end(), {polygon[a], polygon[b], polygon[c]});
    rem.erase(rem.begin() + static_cast<std::ptrdiff_t>(k));
    k = (k + rem.size() - 1) % rem.size();
    misses = 0;
  }
  std::vector<std::uint32_t> rest(rem.size());
  for (std::size_t i = 0; i < rem.size(); ++i) rest[i] = polygon[rem[i]];
  fan(rest, out);
}

Mesh triangulate(const PolygonMesh& polygons) {
  Mesh mesh;
  mesh.positions = polygons.positions;
  const std::size_t n = polygons.positions.size();
  for (std::size_t f = 0; f < polygons.polygons.size(); ++f) {
    const auto& poly = polygons.polygons[f];
    if (poly.size() < 3)
      throw InputError("polygon mesh", "polygon " + std::to_string(f) + " has " + std::to_string(poly.size()) +
                                           " corners (at least 3 needed)");
    for (std::uint32_t i : poly)
      if (i >= n)
        throw InputError("polygon mesh", "polygon " + std::to_string(f) + " uses vertex " + std::to_string(i) +
                                             " but there are only " + std::to_string(n) + " vertices");
    triangulate_polygon(mesh.positions, poly, mesh.indices);
  }
  validate(mesh, "polygon mesh");
  return mesh;
}

}  // namespace facet
