// topology.cpp - connectivity work on meshes: edges, smooth normals, strips, fans, polygon triangulation.
#include <algorithm>
#include <cmath>
#include <span>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <utility>

#include "facet/error.hpp"
#include "facet/mesh.hpp"
#include "scene/mesh/position_key.hpp"

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

using detail::PositionKey;

struct PositionKeyHash {
  std::size_t operator()(const PositionKey& k) const { return static_cast<std::size_t>(detail::position_hash(k)); }
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
