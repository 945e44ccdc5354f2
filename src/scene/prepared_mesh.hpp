// prepared_mesh.hpp - what the Scene caches per mesh: the vertex array, per-material triangle groups, edges, textures.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "facet/mesh.hpp"
#include "facet/shaders/mesh_vertex.hpp"
#include "facet/texture.hpp"

namespace facet::detail {

// The triangles of one material, drawn with one draw call. Per-face data is reordered to match, because
// Fragment::primitive counts triangles within the draw.
struct TriangleGroup {
  std::int32_t material = -1;  // -1: the default material
  std::vector<std::uint32_t> indices;
  // The mesh's index of each triangle of the group; empty when the group is all the mesh's triangles in order (a
  // mesh of one material), which saves 4 bytes a triangle of fresh memory in every render.
  std::vector<std::uint32_t> triangles;
  std::size_t triangle_count() const { return indices.size() / 3; }
  std::uint32_t triangle(std::size_t k) const {
    return triangles.empty() ? static_cast<std::uint32_t>(k) : triangles[k];
  }
  std::vector<glm::vec3> face_normals;   // object space, unit length; by prepare_face_normals
  std::vector<glm::vec4> face_colors;    // empty when the mesh has none (or has vertex colours, which win)
};

struct PreparedMesh {
  std::vector<MeshVertex> vertices;
  std::vector<TriangleGroup> groups;
  // The mesh's points (Mesh::points) as one draw, indices into `vertices`; material -1 (the default material).
  TriangleGroup points;
  bool point_normals = false;  // the mesh has normals of its own, so its points are lit
  // 2 per unique edge, listed by prepare_edges the first time a frame draws edges or a wireframe: sorting a large
  // mesh's edges costs more than drawing it.
  std::vector<std::uint32_t> edge_indices;
  bool edges_prepared = false;
  // Only flat shading reads the groups' face normals (12 bytes a triangle): listed the first time a frame needs them.
  bool face_normals_prepared = false;
  // Where each of the mesh's vertices went when the groups' vertices were laid out apart (empty: nowhere else).
  std::vector<std::uint32_t> first_copy;
  std::vector<const Texture*> textures;  // per material; nullptr = none or failed to load
  bool tangents = false;                 // the vertices carry the file's tangents
  Bounds box;                            // of the positions, object space
  glm::vec3 center{0.0f};                // bounding sphere, object space
  float radius = 0.0f;
};

// Textures by path, loaded once per Scene; a path that failed maps to an empty texture and is not retried.
class TextureCache {
 public:
  // nullptr (after a one-line warning on stderr the first time) when the file cannot be loaded.
  const Texture* get(const std::string& path);

 private:
  std::map<std::string, std::unique_ptr<Texture>> textures_;
};

PreparedMesh prepare_mesh(const Mesh& mesh, TextureCache& textures);

// Lists the edges of the mesh the prepared data came from (once; later calls return at once).
void prepare_edges(PreparedMesh& prepared, const Mesh& mesh);

// Computes each group's face normals from its vertices (once; later calls return at once).
void prepare_face_normals(PreparedMesh& prepared);

}  // namespace facet::detail
