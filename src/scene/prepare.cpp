// prepare.cpp - turns a Mesh into what the stock shaders draw: complete vertices, material groups, edges, textures.
#include <exception>
#include <iostream>

#include "facet/error.hpp"
#include "scene/prepared_mesh.hpp"

namespace facet::detail {

const Texture* TextureCache::get(const std::string& path) {
  auto [it, inserted] = textures_.try_emplace(path);
  if (inserted) {
    try {
      it->second = std::make_unique<Texture>(load_texture(path));
    } catch (const InputError& e) {
      std::cerr << "facet: warning: " << e.what() << '\n';
    } catch (const std::exception& e) {
      std::cerr << "facet: warning: " << path << ": " << e.what() << '\n';
    }
  }
  const Texture* texture = it->second.get();
  return texture && !texture->empty() ? texture : nullptr;
}

namespace {

glm::vec3 face_normal(const std::vector<glm::vec3>& positions, std::uint32_t a, std::uint32_t b, std::uint32_t c) {
  const glm::vec3 n = glm::cross(positions[b] - positions[a], positions[c] - positions[a]);
  const float length = glm::length(n);
  // A degenerate triangle draws nothing, so any unit normal will do.
  return length > 0.0f ? n / length : glm::vec3(0, 0, 1);
}

}  // namespace

PreparedMesh prepare_mesh(const Mesh& mesh, TextureCache& textures) {
  PreparedMesh out;
  const std::size_t n = mesh.positions.size();

  // Smooth normals are computed on a copy so the caller's (shared, const) mesh is untouched.
  std::vector<glm::vec3> smooth;
  const std::vector<glm::vec3>* normals = &mesh.normals;
  if (mesh.normals.size() != n) {
    Mesh copy;
    copy.positions = mesh.positions;
    copy.indices = mesh.indices;
    compute_smooth_normals(copy);
    smooth = std::move(copy.normals);
    normals = &smooth;
  }
  const bool has_uvs = mesh.uvs.size() == n, has_colors = mesh.colors.size() == n;
  out.vertices.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    MeshVertex& v = out.vertices[i];
    v.position = mesh.positions[i];
    v.normal = (*normals)[i];
    v.uv = has_uvs ? mesh.uvs[i] : glm::vec2(0.0f);
    v.color = has_colors ? mesh.colors[i] : glm::vec4(1.0f);
  }

  // Group triangles by material, keeping index order within each group (and the groups in order of first use).
  const std::size_t triangles = mesh.indices.size() / 3;
  const bool has_face_colors = !has_colors && mesh.face_colors.size() == triangles;
  const bool has_face_materials = mesh.face_materials.size() == triangles;
  std::map<std::int32_t, std::size_t> group_of;
  for (std::size_t t = 0; t < triangles; ++t) {
    std::int32_t material = has_face_materials ? mesh.face_materials[t] : -1;
    if (material < -1 || material >= static_cast<std::int32_t>(mesh.materials.size())) material = -1;
    auto [it, inserted] = group_of.try_emplace(material, out.groups.size());
    if (inserted) out.groups.push_back({material, {}, {}, {}});
    TriangleGroup& g = out.groups[it->second];
    const std::uint32_t a = mesh.indices[3 * t], b = mesh.indices[3 * t + 1], c = mesh.indices[3 * t + 2];
    g.indices.insert(g.indices.end(), {a, b, c});
    const bool in_range = a < n && b < n && c < n;
    g.face_normals.push_back(in_range ? face_normal(mesh.positions, a, b, c) : glm::vec3(0, 0, 1));
    if (has_face_colors) g.face_colors.push_back(mesh.face_colors[t]);
  }

  for (const auto& edge : unique_edges(mesh)) out.edge_indices.insert(out.edge_indices.end(), {edge[0], edge[1]});

  // Only materials some triangle uses are loaded, so unused ones cannot cost time or warnings.
  out.textures.assign(mesh.materials.size(), nullptr);
  for (const TriangleGroup& g : out.groups) {
    if (g.material < 0) continue;
    const std::string& path = mesh.materials[static_cast<std::size_t>(g.material)].diffuse_texture;
    if (!path.empty()) out.textures[static_cast<std::size_t>(g.material)] = textures.get(path);
  }

  const Bounds box = bounds(mesh);
  out.center = box.center();
  out.radius = box.radius();
  return out;
}

}  // namespace facet::detail
