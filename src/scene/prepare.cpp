// prepare.cpp - turns a Mesh into what the stock shaders draw: complete vertices, material groups, edges, textures.
#include <algorithm>
#include <array>
#include <cstdint>
#include <exception>
#include <optional>
#include <vector>

#include "facet/error.hpp"
#include "facet/warnings.hpp"
#include "scene/prepared_mesh.hpp"

namespace facet::detail {

const Texture* TextureCache::get(const std::string& path) {
  auto [it, inserted] = textures_.try_emplace(path);
  if (inserted) {
    try {
      it->second = std::make_unique<Texture>(load_texture(path));
    } catch (const InputError& e) {
      warn(e.what());
    } catch (const std::exception& e) {
      warn(path + ": " + e.what());
    }
  }
  const Texture* texture = it->second.get();
  return texture && !texture->empty() ? texture : nullptr;
}

namespace {

// An index no vertex has: one out of range stays so, and a vertex not yet placed is marked with it.
constexpr std::uint32_t kNoVertex = 0xffffffffu;

// Faces more than this angle apart get separate normals at a shared corner (compute_crease_normals). 30 degrees
// (VTK's feature angle, Blender's auto smooth) is too tight for coarse organic models: WusonOBJ with its normals
// removed splits from 2117 vertices into 5064 and its body shades as visible facets, while at 60 it gets 2774 and
// looks much as with its own normals. The edges meant to be hard (a box's 90 degrees and anything sharper) split
// either way.
constexpr float kCreaseAngle = 60.0f * 3.14159265f / 180.0f;

// The Morton code of p within `box` at 10 bits an axis: x, y and z's bits interleaved, so that positions close in
// space mostly have codes close together. A coordinate outside the box or NaN counts as its lowest cell.
std::uint32_t morton_code(const glm::vec3& p, const Bounds& box) {
  const auto cell = [](float t, float low, float high) {
    const float u = high > low ? (t - low) / (high - low) * 1023.0f : 0.0f;
    return u >= 0.0f ? static_cast<std::uint32_t>(std::min(u, 1023.0f)) : 0u;
  };
  const auto spread = [](std::uint32_t v) {  // bit i to bit 3 i
    v = (v | v << 16) & 0x030000ffu;
    v = (v | v << 8) & 0x0300f00fu;
    v = (v | v << 4) & 0x030c30c3u;
    return (v | v << 2) & 0x09249249u;
  };
  return spread(cell(p.x, box.min.x, box.max.x)) | spread(cell(p.y, box.min.y, box.max.y)) << 1 |
         spread(cell(p.z, box.min.z, box.max.z)) << 2;
}

// A cloud's points (a mesh of points alone) in Morton order of their positions, nearby points together: a part of
// the recorded frame then touches few tiles, where a cloud stored in random order touches all of them with every
// part (a 1M-point cloud: 87 against 39 ms a frame at 1920x1080). The file's order is no order a cloud means to be
// drawn in; only which of two points at exactly one depth shows at a pixel can change with it. A stable radix sort of
// the codes, three passes of 10 bits; points naming no vertex go last, in their order. `box` bounds the positions.
std::vector<std::uint32_t> points_in_space_order(const Mesh& mesh, const Bounds& box) {
  const std::size_t count = mesh.points.size(), n = mesh.positions.size();
  std::vector<std::uint32_t> key(count), order(count), sorted(count);
  bool all_named = true;
  for (std::size_t i = 0; i < count; ++i) {
    const std::uint32_t v = mesh.points[i];
    all_named &= v < n;
    key[i] = v < n ? morton_code(mesh.positions[v], box) : std::uint32_t{1} << 30;
    order[i] = static_cast<std::uint32_t>(i);
  }
  constexpr std::uint32_t kBuckets = 1024;
  // The codes take 30 bits; the fourth pass only moves the points naming no vertex, when there are any.
  const int last_shift = all_named ? 20 : 30;
  for (int shift = 0; shift <= last_shift; shift += 10) {
    std::array<std::uint32_t, kBuckets + 1> start{};
    for (const std::uint32_t i : order) ++start[((key[i] >> shift) & (kBuckets - 1)) + 1];
    for (std::uint32_t b = 0; b < kBuckets; ++b) start[b + 1] += start[b];
    for (const std::uint32_t i : order) sorted[start[(key[i] >> shift) & (kBuckets - 1)]++] = i;
    order.swap(sorted);
  }
  return order;
}

glm::vec3 face_normal(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
  const glm::vec3 n = glm::cross(b - a, c - a);
  const float length = glm::length(n);
  // A degenerate triangle draws nothing, so any unit normal will do.
  return length > 0.0f ? n / length : glm::vec3(0, 0, 1);
}

}  // namespace

PreparedMesh prepare_mesh(const Mesh& mesh, TextureCache& textures) {
  PreparedMesh out;
  // Nothing of a mesh without triangles or points goes through the pipeline (a splat scene's centres).
  if (mesh.indices.empty() && mesh.points.empty()) return out;
  const Bounds box = bounds(mesh);
  // A model without normals gets crease normals, computed on a copy because the caller's mesh is shared and const.
  // Splitting at creases appends vertices and re-points indices, so the vertices and triangles come from the copy;
  // the original vertices keep their indices and positions, so edges and bounds still come from the mesh itself
  // (from the copy, an edge along a crease would be listed, and drawn, once per side).
  // A cloud (points, no triangles) has no faces to take normals from: its vertices keep the default normal, as
  // crease normals would give vertices no triangle uses.
  std::optional<Mesh> creased;
  if (mesh.normals.size() != mesh.positions.size() && !mesh.indices.empty()) {
    Mesh& copy = creased.emplace();
    copy.positions = mesh.positions;
    copy.indices = mesh.indices;
    copy.uvs = mesh.uvs;
    copy.uvs1 = mesh.uvs1;
    copy.colors = mesh.colors;
    compute_crease_normals(copy, kCreaseAngle);
  }
  const Mesh& source = creased ? *creased : mesh;
  const std::size_t n = source.positions.size();
  const bool has_uvs = source.uvs.size() == n, has_uvs1 = source.uvs1.size() == n;
  const bool has_colors = source.colors.size() == n, has_normals = source.normals.size() == n;
  // Crease normals replace the file's (it had none), so its tangents are dropped with them.
  out.tangents = !creased && source.tangents.size() == n;
  // A cloud's vertices in the order its points are drawn in (points_in_space_order), each once, so that the vertex
  // stage and setup read them in order too; vertices no point names are left out.
  std::vector<std::uint32_t> placed;  // placed[i]: the source vertex of prepared vertex i, where a cloud is ordered
  if (mesh.indices.empty()) {
    std::vector<std::uint32_t> place(n, kNoVertex);
    out.points.indices.reserve(mesh.points.size());
    placed.reserve(std::min(n, mesh.points.size()));
    for (const std::uint32_t p : points_in_space_order(mesh, box)) {
      const std::uint32_t v = mesh.points[p];
      if (v >= n) {
        out.points.indices.push_back(kNoVertex);
        continue;
      }
      if (place[v] == kNoVertex) {
        place[v] = static_cast<std::uint32_t>(placed.size());
        placed.push_back(v);
      }
      out.points.indices.push_back(place[v]);
    }
  }
  const std::size_t m = mesh.indices.empty() ? placed.size() : n;
  out.vertices.resize(m);
  for (std::size_t k = 0; k < m; ++k) {
    const std::size_t i = mesh.indices.empty() ? placed[k] : k;
    MeshVertex& v = out.vertices[k];
    v.position = source.positions[i];
    v.normal = has_normals ? source.normals[i] : glm::vec3(0.0f, 0.0f, 1.0f);
    v.uv = has_uvs ? source.uvs[i] : glm::vec2(0.0f);
    v.uv1 = has_uvs1 ? source.uvs1[i] : glm::vec2(0.0f);
    v.color = has_colors ? source.colors[i] : glm::vec4(1.0f);
    if (out.tangents) v.tangent = source.tangents[i];
  }

  // Group triangles by material, keeping index order within each group (and the groups in order of first use).
  const std::size_t triangles = mesh.indices.size() / 3;
  const bool has_face_colors = !has_colors && mesh.face_colors.size() == triangles;
  const bool has_face_materials = mesh.face_materials.size() == triangles;
  // First each triangle's group, counting the groups' sizes, so each group's arrays are allocated once at their
  // size: grown by doubling, an 870k-triangle mesh's moved and faulted in 50 MB more than it keeps.
  const auto material_of_triangle = [&](std::size_t t) {
    const std::int32_t material = has_face_materials ? mesh.face_materials[t] : -1;
    return material < -1 || material >= static_cast<std::int32_t>(mesh.materials.size()) ? -1 : material;
  };
  std::map<std::int32_t, std::size_t> group_of;
  std::vector<std::size_t> group_size;
  std::int32_t last_material = 0;
  std::size_t last_group = 0;
  for (std::size_t t = 0; t < triangles; ++t) {
    const std::int32_t material = material_of_triangle(t);
    if (t == 0 || material != last_material) {
      auto [it, inserted] = group_of.try_emplace(material, out.groups.size());
      if (inserted) {
        out.groups.push_back({material, {}, {}, {}, {}});
        group_size.push_back(0);
      }
      last_material = material;
      last_group = it->second;
    }
    ++group_size[last_group];
  }
  // One group takes the triangles' indices whole: moved from the creased copy, which is done with them.
  const bool one_group = out.groups.size() == 1;
  if (one_group) {
    std::vector<std::uint32_t>& indices = out.groups[0].indices;
    indices = creased ? std::move(creased->indices) : mesh.indices;
    indices.resize(3 * triangles);
  }
  const std::vector<std::uint32_t>& corner_indices = one_group ? out.groups[0].indices : source.indices;
  for (std::size_t g = 0; g < out.groups.size(); ++g) {
    if (!one_group) out.groups[g].indices.reserve(3 * group_size[g]);
    if (!one_group) out.groups[g].triangles.reserve(group_size[g]);
    if (has_face_colors) out.groups[g].face_colors.reserve(group_size[g]);
  }
  for (std::size_t t = 0; t < triangles; ++t) {
    const std::int32_t material = material_of_triangle(t);
    if (t == 0 || material != last_material) {
      last_material = material;
      last_group = group_of.find(material)->second;
    }
    TriangleGroup& g = out.groups[last_group];
    const std::uint32_t a = corner_indices[3 * t], b = corner_indices[3 * t + 1], c = corner_indices[3 * t + 2];
    if (!one_group) {
      g.indices.insert(g.indices.end(), {a, b, c});
      g.triangles.push_back(static_cast<std::uint32_t>(t));
    }
    if (has_face_colors) g.face_colors.push_back(mesh.face_colors[t]);
  }

  // Each group's vertices, contiguous and in order of first use. A draw shades the band of vertices its indices
  // span, so groups whose vertices interleave in the array (a glTF's primitives merged by material) would each
  // shade most of it. A vertex that several groups use is copied into each; edges take its first copy.
  if (out.groups.size() > 1) {
    std::vector<MeshVertex> ordered;
    ordered.reserve(n);
    out.first_copy.assign(n, kNoVertex);
    std::vector<std::uint32_t> copy_in_group(n, kNoVertex), group_of_copy(n, kNoVertex);
    for (std::uint32_t g = 0; g < out.groups.size(); ++g) {
      for (std::uint32_t& index : out.groups[g].indices) {
        if (index >= n) {
          index = kNoVertex;  // stays out of range however many copies are added
          continue;
        }
        if (group_of_copy[index] != g) {
          group_of_copy[index] = g;
          copy_in_group[index] = static_cast<std::uint32_t>(ordered.size());
          ordered.push_back(out.vertices[index]);
          if (out.first_copy[index] == kNoVertex) out.first_copy[index] = copy_in_group[index];
        }
        index = copy_in_group[index];
      }
    }
    // A vertex no triangle uses keeps a place, for an edge that might name it.
    for (std::size_t v = 0; v < n; ++v) {
      if (out.first_copy[v] != kNoVertex) continue;
      out.first_copy[v] = static_cast<std::uint32_t>(ordered.size());
      ordered.push_back(out.vertices[v]);
    }
    out.vertices = std::move(ordered);
  }

  // Points beside triangles name the mesh's vertices in the file's order; where the groups' vertices were laid out
  // apart, each takes its first copy.
  if (!mesh.indices.empty()) {
    out.points.indices.reserve(mesh.points.size());
    for (const std::uint32_t v : mesh.points)
      out.points.indices.push_back(v >= n ? kNoVertex : out.first_copy.empty() ? v : out.first_copy[v]);
  }
  out.point_normals = mesh.normals.size() == mesh.positions.size();
  // An index out of range (a mesh that skipped validate()) draws the points in the default material.
  if (mesh.point_material >= 0 && static_cast<std::size_t>(mesh.point_material) < mesh.materials.size())
    out.points.material = mesh.point_material;

  // Only materials some triangle uses are loaded, so unused ones cannot cost time or warnings.
  out.textures.assign(mesh.materials.size(), nullptr);
  for (const TriangleGroup& g : out.groups) {
    if (g.material < 0) continue;
    const Material& material = mesh.materials[static_cast<std::size_t>(g.material)];
    const Texture* texture = material.diffuse_map.get();
    if (!texture && !material.diffuse_texture.empty()) texture = textures.get(material.diffuse_texture);
    out.textures[static_cast<std::size_t>(g.material)] = texture && !texture->empty() ? texture : nullptr;
  }

  out.box = box;
  out.center = box.center();
  out.radius = box.radius();
  return out;
}

void prepare_face_normals(PreparedMesh& prepared) {
  if (prepared.face_normals_prepared) return;
  const std::vector<MeshVertex>& vertices = prepared.vertices;
  const std::size_t n = vertices.size();
  for (TriangleGroup& g : prepared.groups) {
    g.face_normals.resize(g.indices.size() / 3);
    for (std::size_t t = 0; t < g.face_normals.size(); ++t) {
      const std::uint32_t a = g.indices[3 * t], b = g.indices[3 * t + 1], c = g.indices[3 * t + 2];
      g.face_normals[t] = a < n && b < n && c < n
                              ? face_normal(vertices[a].position, vertices[b].position, vertices[c].position)
                              : glm::vec3(0, 0, 1);
    }
  }
  prepared.face_normals_prepared = true;
}

void prepare_edges(PreparedMesh& prepared, const Mesh& mesh) {
  if (prepared.edges_prepared) return;
  const std::vector<std::array<std::uint32_t, 2>> edges = unique_edges(mesh);
  const std::vector<std::uint32_t>& moved = prepared.first_copy;
  prepared.edge_indices.reserve(2 * edges.size());
  for (const auto& edge : edges)
    for (const std::uint32_t end : edge)
      prepared.edge_indices.push_back(moved.empty() ? end : end < moved.size() ? moved[end] : kNoVertex);
  prepared.edges_prepared = true;
}

}  // namespace facet::detail
