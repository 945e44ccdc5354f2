// mesh.cpp - mesh validation, bounds and reading meshes out of interleaved float vertex buffers.
#include "facet/mesh.hpp"

#include <cmath>
#include <cstring>
#include <limits>
#include <string>

#include "facet/error.hpp"

namespace facet {

namespace {

bool finite(const glm::vec3& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z); }

template <typename T>
void check_per_vertex(const std::vector<T>& attribute, const char* name, std::size_t vertices,
                      const std::string& source) {
  if (!attribute.empty() && attribute.size() != vertices)
    throw InputError(source, std::string(name) + " has " + std::to_string(attribute.size()) +
                                 " entries but there are " + std::to_string(vertices) + " positions");
}

template <typename T>
void check_per_triangle(const std::vector<T>& attribute, const char* name, std::size_t triangles,
                        const std::string& source) {
  if (!attribute.empty() && attribute.size() != triangles)
    throw InputError(source, std::string(name) + " has " + std::to_string(attribute.size()) +
                                 " entries but there are " + std::to_string(triangles) + " triangles");
}

}  // namespace

void validate(const Mesh& mesh, const std::string& source) {
  const std::size_t n = mesh.positions.size();
  check_per_vertex(mesh.normals, "normals", n, source);
  check_per_vertex(mesh.uvs, "uvs", n, source);
  check_per_vertex(mesh.uvs1, "uvs1", n, source);
  check_per_vertex(mesh.tangents, "tangents", n, source);
  check_per_vertex(mesh.colors, "colors", n, source);
  check_per_vertex(mesh.intensities, "intensities", n, source);
  if (mesh.indices.size() % 3 != 0)
    throw InputError(source, "index count " + std::to_string(mesh.indices.size()) + " is not a multiple of 3");
  const std::size_t triangles = mesh.triangle_count();
  check_per_triangle(mesh.face_colors, "face_colors", triangles, source);
  check_per_triangle(mesh.face_materials, "face_materials", triangles, source);
  check_per_triangle(mesh.face_ids, "face_ids", triangles, source);
  check_per_triangle(mesh.instance_ids, "instance_ids", triangles, source);
  if (triangles >= kNoSurface)
    throw InputError(source, std::to_string(triangles) + " triangles: more than 32-bit ids can number");
  for (const auto* ids : {&mesh.face_ids, &mesh.instance_ids})
    for (std::size_t t = 0; t < ids->size(); ++t)
      if ((*ids)[t] == kNoSurface)
        throw InputError(source,
                         "triangle " + std::to_string(t) + " has the reserved id " + std::to_string(kNoSurface));
  for (std::size_t i = 0; i < mesh.points.size(); ++i)
    if (mesh.points[i] >= n)
      throw InputError(source, "point " + std::to_string(i) + " is vertex " + std::to_string(mesh.points[i]) +
                                   " but there are only " + std::to_string(n) + " vertices");
  for (std::size_t i = 0; i < mesh.indices.size(); ++i)
    if (mesh.indices[i] >= n)
      throw InputError(source, "index " + std::to_string(i) + " (triangle " + std::to_string(i / 3) + ") is " +
                                   std::to_string(mesh.indices[i]) + " but there are only " + std::to_string(n) +
                                   " vertices");
  for (std::size_t t = 0; t < mesh.face_materials.size(); ++t) {
    const std::int32_t m = mesh.face_materials[t];
    if (m < -1 || (m >= 0 && static_cast<std::size_t>(m) >= mesh.materials.size()))
      throw InputError(source, "triangle " + std::to_string(t) + " uses material " + std::to_string(m) +
                                   " but there are " + std::to_string(mesh.materials.size()) + " materials");
  }
  if (mesh.point_material < -1 || (mesh.point_material >= 0 &&
                                    static_cast<std::size_t>(mesh.point_material) >= mesh.materials.size()))
    throw InputError(source, "the points use material " + std::to_string(mesh.point_material) + " but there are " +
                                 std::to_string(mesh.materials.size()) + " materials");
  for (std::size_t v = 0; v < n; ++v)
    if (!finite(mesh.positions[v]))
      throw InputError(source, "non-finite vertex position (vertex " + std::to_string(v) + ")");
}

Bounds bounds(const Mesh& mesh) {
  Bounds b;
  for (const glm::vec3& p : mesh.positions) {
    if (!finite(p)) continue;
    b.min = glm::min(b.min, p);
    b.max = glm::max(b.max, p);
  }
  return b;
}

namespace {

const char* const kInterleaved = "interleaved buffer";

// Checks that an attribute of `bytes` bytes at `offset` fits inside one record; the comparison is written so that
// a huge offset cannot overflow.
void check_fits(const char* name, std::size_t offset, std::size_t bytes, std::size_t stride) {
  if (offset > stride || bytes > stride - offset)
    throw InputError(kInterleaved, std::string(name) + " at offset " + std::to_string(offset) + " (" +
                                       std::to_string(bytes) + " bytes) does not fit in a " + std::to_string(stride) +
                                       "-byte vertex");
}

template <int N>
glm::vec<N, float> read_floats(std::span<const std::byte> data, std::size_t at) {
  float f[N];
  std::memcpy(f, data.data() + at, sizeof f);  // memcpy: the buffer may be unaligned
  glm::vec<N, float> v;
  for (int i = 0; i < N; ++i) v[i] = f[i];
  return v;
}

}  // namespace

Mesh mesh_from_interleaved(std::span<const std::byte> data, const VertexLayout& layout,
                           std::span<const std::uint32_t> indices) {
  const std::size_t stride = layout.stride;
  if (stride == 0) throw InputError(kInterleaved, "stride is 0");
  if (layout.color_components != 3 && layout.color_components != 4)
    throw InputError(kInterleaved,
                     "color_components is " + std::to_string(layout.color_components) + " (must be 3 or 4)");
  check_fits("position", layout.position_offset, 3 * sizeof(float), stride);
  if (layout.normal_offset) check_fits("normal", *layout.normal_offset, 3 * sizeof(float), stride);
  if (layout.uv_offset) check_fits("uv", *layout.uv_offset, 2 * sizeof(float), stride);
  if (layout.color_offset)
    check_fits("color", *layout.color_offset, static_cast<std::size_t>(layout.color_components) * sizeof(float),
               stride);
  if (data.empty()) throw InputError(kInterleaved, "buffer is empty");
  if (data.size() % stride != 0)
    throw InputError(kInterleaved, "buffer of " + std::to_string(data.size()) + " bytes is not a whole number of " +
                                       std::to_string(stride) + "-byte vertices");
  const std::size_t count = data.size() / stride;
  if (count > std::numeric_limits<std::uint32_t>::max())
    throw InputError(kInterleaved, "too many vertices (" + std::to_string(count) + ") for 32-bit indices");
  if (indices.empty() && count % 3 != 0)
    throw InputError(kInterleaved,
                     "non-indexed buffer has " + std::to_string(count) + " vertices, which is not a multiple of 3");
  if (indices.size() % 3 != 0)
    throw InputError(kInterleaved, "index count " + std::to_string(indices.size()) + " is not a multiple of 3");

  Mesh mesh;
  mesh.positions.reserve(count);
  for (std::size_t k = 0; k < count; ++k) {
    const std::size_t base = k * stride;
    mesh.positions.push_back(read_floats<3>(data, base + layout.position_offset));
    if (layout.normal_offset) mesh.normals.push_back(read_floats<3>(data, base + *layout.normal_offset));
    if (layout.uv_offset) mesh.uvs.push_back(read_floats<2>(data, base + *layout.uv_offset));
    if (layout.color_offset) {
      const std::size_t at = base + *layout.color_offset;
      mesh.colors.push_back(layout.color_components == 4 ? read_floats<4>(data, at)
                                                         : glm::vec4(read_floats<3>(data, at), 1.0f));
    }
  }
  if (indices.empty()) {
    mesh.indices.resize(count);
    for (std::size_t k = 0; k < count; ++k) mesh.indices[k] = static_cast<std::uint32_t>(k);
  } else {
    mesh.indices.assign(indices.begin(), indices.end());
  }
  validate(mesh, kInterleaved);
  return mesh;
}

}  // namespace facet
