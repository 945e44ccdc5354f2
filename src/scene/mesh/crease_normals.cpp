// crease_normals.cpp - vertex normals that stay smooth within a crease angle and split across it, on a few threads.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <span>
#include <stdexcept>
#include <thread>
#include <vector>

#include "facet/detail/bits.hpp"
#include "facet/detail/default_init.hpp"
#include "facet/framebuffer.hpp"
#include "facet/mesh.hpp"
#include "core/in_parts.hpp"
#include "scene/mesh/crease_normals.hpp"
#include "scene/mesh/position_key.hpp"

namespace facet {

namespace {

using detail::in_parts;
using detail::part_begin;
using detail::PositionKey;
using NormalBits = std::array<std::uint32_t, 3>;

// The crease normals' large temporaries (tens of MB for a million triangles) are written once, right after
// allocation: on huge pages (CacheAlignedAllocator) that costs one fault per 2 MiB rather than one per 4 KiB. Their
// elements are default-initialised (left unset, for these types) rather than zeroed: each is written before it is
// read, and zeroing first would write every byte twice (a memset was 18% of an 870k-triangle PLY's render).
template <class T>
using Scratch = std::vector<T, detail::DefaultInitAllocator<CacheAlignedAllocator<T>>>;

// How many threads the passes over triangles, groups and vertices take: one per 64k triangles, at most 4 and the
// cores. The result is the same for any count (each pass below says why). The browser build has no threads.
int parts_for(std::size_t triangles) {
#if defined(__EMSCRIPTEN__)
  (void)triangles;
  return 1;
#else
  const std::size_t cores = std::max(1u, std::thread::hardware_concurrency());
  return static_cast<int>(std::clamp<std::size_t>(triangles / 65536, 1, std::min<std::size_t>(cores, 4)));
#endif
}

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
  const auto hash_of = [&](std::size_t v) { return detail::position_hash(PositionKey(positions[v])); };
  constexpr std::size_t kAhead = 16;
  std::uint32_t groups = 0;
  for (std::size_t v = 0; v < n; ++v) {
    if (v + kAhead < n) __builtin_prefetch(&slots[hash_of(v + kAhead) & (capacity - 1)]);
    const PositionKey key(positions[v]);
    const std::uint64_t hash = detail::position_hash(key);
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
    Corner stop;  // the range's end, which settle() does not pass
    Corner operator*() const { return c; }
    Iterator& operator++() {
      ++c;
      if (c % 3 == 0) settle();
      return *this;
    }
    // Moves c past any unusable triangles starting at it.
    void settle() {
      while (c != stop && skip != skip_end && *skip == c / 3) {
        c += 3;
        ++skip;
      }
    }
    bool operator!=(const Iterator& other) const { return c != other.c; }
  };
  std::span<const std::size_t> skipped;
  std::size_t triangles;
  // The usable corners of triangles [first, last).
  struct Range {
    Iterator b, e;
    Iterator begin() const { return b; }
    Iterator end() const { return e; }
  };
  Range of(std::size_t first, std::size_t last) const {
    const std::size_t* skip = std::lower_bound(skipped.data(), skipped.data() + skipped.size(), first);
    const auto stop = static_cast<Corner>(3 * last);
    Iterator b{static_cast<Corner>(3 * first), skip, skipped.data() + skipped.size(), stop};
    b.settle();
    return {b, Iterator{stop, nullptr, nullptr, stop}};
  }
  std::size_t size() const { return 3 * (triangles - skipped.size()); }
};

// Counting sort of the usable corners by key (key(corner) < buckets): start gets buckets + 1 offsets, sorted the
// corners bucket by bucket, each bucket keeping the corners' order. Each part counts and then places the corners of
// its own range of triangles, and the parts' offsets within a bucket follow the parts' order, so the order is the
// same on any number of threads. Reuses the vectors' storage when called again.
template <typename Key>
void bucket(const UsableCorners& items, std::size_t buckets, int parts, std::vector<Scratch<Corner>>& counts,
            Scratch<Corner>& start, Scratch<Corner>& sorted, Key key) {
  counts.resize(static_cast<std::size_t>(parts));
  for (Scratch<Corner>& c : counts) c.resize(buckets);
  start.resize(buckets + 1);
  sorted.resize(items.size());
  const auto range = [&](int p) {
    return items.of(part_begin(items.triangles, p, parts), part_begin(items.triangles, p + 1, parts));
  };
  in_parts(parts, [&](int p) {
    Scratch<Corner>& count = counts[static_cast<std::size_t>(p)];
    std::fill(count.begin(), count.end(), Corner{0});
    for (Corner item : range(p)) ++count[key(item)];
  });
  // Each part's count becomes where its corners of that bucket go.
  Corner next = 0;
  for (std::size_t b = 0; b < buckets; ++b) {
    start[b] = next;
    for (Scratch<Corner>& count : counts) {
      const Corner c = count[b];
      count[b] = next;
      next += c;
    }
  }
  start[buckets] = next;
  in_parts(parts, [&](int p) {
    Scratch<Corner>& place = counts[static_cast<std::size_t>(p)];
    for (Corner item : range(p)) sorted[place[key(item)]++] = item;
  });
}

}  // namespace

void compute_crease_normals(Mesh& mesh, float crease_angle_radians) {
  detail::compute_crease_normals_in_parts(mesh, crease_angle_radians, parts_for(mesh.indices.size() / 3));
}

void detail::compute_crease_normals_in_parts(Mesh& mesh, float crease_angle_radians, int parts) {
  const std::size_t n = mesh.positions.size();
  const std::size_t triangles = mesh.indices.size() / 3;
  if (mesh.indices.size() > std::numeric_limits<Corner>::max())
    throw std::length_error("compute_crease_normals: more indices than 32-bit corner numbers can address");
  parts = std::max(parts, 1);
  Scratch<std::uint32_t> group;
  const std::size_t group_count = group_by_position(mesh.positions, group);

  // Per triangle, the unnormalised face normal (twice the area long: the weight, computed as in
  // compute_smooth_normals so a 180 degree crease reproduces it bit for bit). The unit normal for the angle test is
  // computed from it where a group needs it (unit_of): stored, it would be ten more megabytes a million triangles.
  // Triangles with an index out of range, zero area or a non-finite normal are unusable: they add nothing and keep
  // their indices, so a degenerate triangle can neither split a vertex nor make a NaN. Each part lists its own
  // unusable triangles; joined in the parts' order, the list is in triangle order.
  Scratch<glm::vec3> area(triangles);
  std::vector<std::vector<std::size_t>> unusable_in(static_cast<std::size_t>(parts));
  in_parts(parts, [&](int p) {
    std::vector<std::size_t>& unusable = unusable_in[static_cast<std::size_t>(p)];
    for (std::size_t t = part_begin(triangles, p, parts); t < part_begin(triangles, p + 1, parts); ++t) {
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
  });
  std::vector<std::size_t> unusable;  // in order; usually none
  for (const std::vector<std::size_t>& part : unusable_in) unusable.insert(unusable.end(), part.begin(), part.end());
  const auto unit_of = [&](Corner c) {
    const glm::vec3& a = area[c / 3];
    return a / std::sqrt(glm::dot(a, a));
  };
  const UsableCorners usable_corners{unusable, triangles};
  std::vector<Scratch<Corner>> counts;  // the counting sorts' per-part counts (bucket), reused
  Scratch<Corner> start, bucketed;      // their output, reused
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
  bucket(usable_corners, group_count, parts, counts, start, bucketed,
         [&](Corner c) { return group[mesh.indices[c]]; });
  const auto members_of = [&](std::size_t g) {
    return std::span<const Corner>(bucketed.data() + start[g], bucketed.data() + start[g + 1]);
  };

  // Each corner's normal, as an index into `normals`: the groups' smooth normals first (the normal of nearly every
  // corner), then the normals of crease-split corners as they are found. Four bytes a corner rather than twelve.
  Scratch<std::uint32_t> corner_normal(mesh.indices.size());
  Scratch<glm::vec3> normals;
  normals.reserve(group_count + group_count / 8);
  normals.resize(group_count);
  // The groups' smooth normals on the threads, and the groups that a crease crosses, in group order per part: those
  // are split afterwards on one thread, in group order, so the split normals are numbered as on one thread.
  std::vector<std::vector<std::uint32_t>> creased_in(static_cast<std::size_t>(parts));
  in_parts(parts, [&](int p) {
    for (std::size_t g = part_begin(group_count, p, parts); g < part_begin(group_count, p + 1, parts); ++g) {
      const std::span<const Corner> members = members_of(g);
      // The plain area-weighted sum over the group, in triangle order: the smooth normal. Every corner whose faces
      // are all within the crease angle gets exactly these bits, which is what keeps smooth regions' vertices
      // shared.
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
      creased_in[static_cast<std::size_t>(p)].push_back(static_cast<std::uint32_t>(g));
    }
  });

  // A creased group: each distinct face normal sums the faces within the angle of it: O(distinct x members), where
  // the distinct normals are few except at the apex of a sharp cone-like fan.
  std::vector<glm::vec3> member_unit;  // the group's unit face normals, one per member
  std::vector<std::uint32_t> by_normal;  // the members' places sorted by them
  for (const std::vector<std::uint32_t>& creased : creased_in)
    for (const std::uint32_t g : creased) {
      const std::span<const Corner> members = members_of(g);
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
  bucket(usable_corners, n, parts, counts, start, bucketed, [&](Corner c) { return mesh.indices[c]; });
  const auto bits = [&](Corner c) { return bits_of(normals[corner_normal[c]]); };
  const auto normal_less = [&](Corner a, Corner b) { return bits(a) < bits(b); };
  const auto same_normal = [&](Corner a, Corner b) {
    return corner_normal[a] == corner_normal[b] || bits(a) == bits(b);
  };
  // Per part of the vertices, how many copies its vertices need; the parts' copies are appended in the parts'
  // order, so each vertex's copies land where one thread would put them.
  std::vector<std::size_t> copies(static_cast<std::size_t>(parts) + 1, 0);
  in_parts(parts, [&](int p) {
    std::size_t& added = copies[static_cast<std::size_t>(p) + 1];
    for (std::size_t v = part_begin(n, p, parts); v < part_begin(n, p + 1, parts); ++v) {
      Corner* const first = bucketed.data() + start[v];
      Corner* const last = bucketed.data() + start[v + 1];
      // Most vertices' corners all share one normal: nothing to sort or split there.
      if (std::all_of(first, last, [&](Corner c) { return corner_normal[c] == corner_normal[*first]; })) continue;
      std::sort(first, last, normal_less);
      for (Corner i = start[v] + 1; i < start[v + 1]; ++i) added += !same_normal(bucketed[i], bucketed[i - 1]);
    }
  });
  for (int p = 0; p < parts; ++p) copies[static_cast<std::size_t>(p) + 1] += copies[static_cast<std::size_t>(p)];
  const std::size_t total = n + copies.back();
  if (std::uint64_t{total} > std::uint64_t{std::numeric_limits<std::uint32_t>::max()} + 1)
    throw std::length_error("compute_crease_normals: more vertices than 32-bit indices can address");

  // Attributes with one entry per vertex are copied along; a wrongly sized one is left alone (the mesh was already
  // invalid, and users check sizes against positions).
  const bool copy_uvs = mesh.uvs.size() == n, copy_uvs1 = mesh.uvs1.size() == n, copy_colors = mesh.colors.size() == n;
  const bool copy_intensities = mesh.intensities.size() == n;
  mesh.positions.resize(total);
  mesh.normals.assign(total, glm::vec3(0, 0, 1));
  mesh.tangents.clear();  // made for the normals replaced here
  if (copy_uvs) mesh.uvs.resize(total);
  if (copy_uvs1) mesh.uvs1.resize(total);
  if (copy_colors) mesh.colors.resize(total);
  if (copy_intensities) mesh.intensities.resize(total);
  in_parts(parts, [&](int p) {
    std::size_t next = n + copies[static_cast<std::size_t>(p)];
    for (std::size_t v = part_begin(n, p, parts); v < part_begin(n, p + 1, parts); ++v) {
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
          if (copy_intensities) mesh.intensities[target] = mesh.intensities[v];
        } else {
          target = mesh.indices[bucketed[i - 1]];  // same run as the previous corner, already re-pointed
        }
        mesh.indices[c] = static_cast<std::uint32_t>(target);
      }
    }
  });
}

}  // namespace facet
