// obj_loader.cpp - load_obj(): Wavefront OBJ (facet's parser) + MTL (tinyobjloader's), checked, indexed, triangulated.
#include <tiny_obj_loader.h>

#include <algorithm>
#include <cmath>
#include <istream>
#include <map>
#include <string>
#include <string_view>
#include <unordered_map>

#include "facet/color.hpp"
#include "facet/error.hpp"
#include "facet/model_io.hpp"
#include "core/file_util.hpp"
#include "job/io/loaders.hpp"
#include "job/io/obj_parse.hpp"

namespace facet {

namespace fs = std::filesystem;

namespace {

// Lets tinyobj's MTL reader read the file's bytes in place; an istringstream would copy them.
class ViewBuffer : public std::streambuf {
 public:
  explicit ViewBuffer(FileBytes& text) { setg(text.data(), text.data(), text.data() + text.size()); }
};

// Reads MTL files from the .obj's folder tree (references.hpp) with tinyobjloader's MTL parser, warning in facet's
// format when one cannot be used.
class MtlReader {
 public:
  MtlReader(ReferencePolicy policy, std::string source) : policy_(std::move(policy)), source_(std::move(source)) {}

  bool operator()(const std::string& name, std::map<std::string, int>& names) {
    const std::string what = "material library '" + printable(name) + "'";
    const Reference found = resolve_reference(policy_, name);
    if (!found.note.empty()) warn(source_, what + " " + printable(found.note));
    if (!found.path) {
      warn(source_, what + ": " + printable(found.problem) + "; faces keep no material");
      return false;
    }
    FileBytes text;
    try {
      text = read_regular_file(*found.path, kMaxModelFileBytes, found.path->string());
    } catch (const InputError& e) {
      warn(source_, what + ": " + e.what() + "; faces keep no material");
      return false;
    }
    ViewBuffer buffer(text);
    std::istream in(&buffer);
    std::string warnings, errors;
    tinyobj::LoadMtl(&names, &materials, &in, &warnings, &errors);
    return true;
  }

  std::vector<tinyobj::material_t> materials;

 private:
  ReferencePolicy policy_;
  std::string source_;
};

struct CornerKey {
  int v, vt, vn;
  bool operator==(const CornerKey& o) const { return v == o.v && vt == o.vt && vn == o.vn; }
};

struct CornerKeyHash {
  std::size_t operator()(const CornerKey& k) const {
    std::uint64_t h = static_cast<std::uint32_t>(k.v);
    h = h * 0x9e3779b97f4a7c15ull + static_cast<std::uint32_t>(k.vt);
    h = h * 0x9e3779b97f4a7c15ull + static_cast<std::uint32_t>(k.vn);
    return static_cast<std::size_t>(h ^ (h >> 32));
  }
};

// A file of `v` lines and no faces is a point cloud: each position a point, with its colour where every `v` line has
// one (`vn` lines name no vertex, so a cloud has no normals).
Mesh point_cloud(const ObjData& obj) {
  Mesh mesh;
  const std::size_t n = obj.positions.size() / 3;
  mesh.positions.resize(n);
  for (std::size_t i = 0; i < n; ++i)
    mesh.positions[i] = {obj.positions[3 * i], obj.positions[3 * i + 1], obj.positions[3 * i + 2]};
  if (!obj.colors.empty() && obj.colors.size() == obj.positions.size()) {
    mesh.colors.resize(n);
    for (std::size_t i = 0; i < n; ++i)
      mesh.colors[i] = {obj.colors[3 * i], obj.colors[3 * i + 1], obj.colors[3 * i + 2], 1.0f};
  }
  mesh.points_at_every_vertex();
  return mesh;
}

// Builds the indexed mesh from the parsed polygons: one vertex per distinct (v, vt, vn) corner.
class MeshBuilder {
 public:
  MeshBuilder(const ObjData& obj, std::size_t material_count, std::string source)
      : obj_(obj),
        positions_(obj.positions.size() / 3),
        normals_(obj.normals.size() / 3),
        uvs_(obj.uvs.size() / 2),
        has_colors_(!obj.colors.empty() && obj.colors.size() == obj.positions.size()),
        material_count_(material_count),
        source_(std::move(source)) {}

  Mesh build() {
    // A polygon of n corners becomes n - 2 triangles; there are at most as many vertices as corners, or as
    // positions when no corner names a texture coordinate or normal.
    const std::size_t corners = obj_.corners.size(), faces = obj_.face_ends.size();
    mesh_.indices.reserve(3 * (corners - 2 * faces));
    face_materials_.reserve(corners - 2 * faces);
    const std::size_t vertices = obj_.uvs.empty() && obj_.normals.empty() ? std::min(corners, positions_) : corners;
    mesh_.positions.reserve(vertices);
    if (!obj_.normals.empty()) mesh_.normals.reserve(vertices);
    if (!obj_.uvs.empty()) mesh_.uvs.reserve(vertices);
    if (has_colors_) mesh_.colors.reserve(vertices);
    std::vector<std::uint32_t> polygon;
    std::uint32_t first = 0;
    for (std::size_t f = 0; f < obj_.face_ends.size(); ++f) {
      const std::uint32_t end = obj_.face_ends[f];
      // Ear clipping takes quadratic time in the corners, so a polygon's are bounded.
      if (end - first > kMaxPolygonCorners)
        throw InputError(source_, "a polygon has more than 255 corners (not supported)");
      polygon.clear();
      for (std::uint32_t k = first; k < end; ++k) polygon.push_back(vertex_for(obj_.corners[k]));
      first = end;
      const std::size_t before = mesh_.indices.size();
      triangulate_polygon(mesh_.positions, polygon, mesh_.indices);
      faces_.add_face(mesh_, before / 3);
      const int id = obj_.face_materials[f];
      const std::int32_t material = (id >= 0 && static_cast<std::size_t>(id) < material_count_) ? id : -1;
      face_materials_.insert(face_materials_.end(), (mesh_.indices.size() - before) / 3, material);
    }
    if (!all_normals_) mesh_.normals.clear();
    if (!all_uvs_) mesh_.uvs.clear();
    if (material_count_ > 0) mesh_.face_materials = std::move(face_materials_);
    return std::move(mesh_);
  }

 private:
  [[noreturn]] void out_of_range(const char* what, int index, std::size_t count) const {
    const std::string which = index >= 0 ? std::to_string(index + 1) : "before the first (relative index)";
    throw InputError(
        source_, std::string("a face references ") + what + " " + which + " but the file has " + std::to_string(count));
  }

  std::uint32_t vertex_for(const ObjCorner& corner) {
    const int v = corner.v, vt = corner.vt, vn = corner.vn;
    if (v < 0 || static_cast<std::size_t>(v) >= positions_) out_of_range("vertex", v, positions_);
    if (vt < -1 || (vt >= 0 && static_cast<std::size_t>(vt) >= uvs_)) out_of_range("texture coordinate", vt, uvs_);
    if (vn < -1 || (vn >= 0 && static_cast<std::size_t>(vn) >= normals_)) out_of_range("normal", vn, normals_);
    // A corner with only a position ("f 1 2 3") is looked up by position in an array; the others by all three.
    std::uint32_t* slot;
    if (vt < 0 && vn < 0) {
      if (by_position_.empty()) by_position_.assign(positions_, kNoVertex);
      slot = &by_position_[static_cast<std::size_t>(v)];
    } else {
      slot = &index_.try_emplace(CornerKey{v, vt, vn}, kNoVertex).first->second;
    }
    if (*slot != kNoVertex) return *slot;
    if (mesh_.positions.size() >= kNoVertex) throw InputError(source_, "too many distinct vertices for 32-bit indices");
    *slot = static_cast<std::uint32_t>(mesh_.positions.size());

    const ObjData& o = obj_;
    const std::size_t pv = 3 * static_cast<std::size_t>(v);
    const glm::vec3 p(o.positions[pv], o.positions[pv + 1], o.positions[pv + 2]);
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      throw InputError(source_, "non-finite vertex position (vertex " + std::to_string(v + 1) + ")");
    mesh_.positions.push_back(p);
    all_normals_ = all_normals_ && vn >= 0;
    all_uvs_ = all_uvs_ && vt >= 0;
    const std::size_t pn = 3 * static_cast<std::size_t>(vn), pt = 2 * static_cast<std::size_t>(vt);
    // A mesh keeps normals (texture coordinates) only if every vertex has one, so after the first vertex without,
    // none are kept.
    if (all_normals_) mesh_.normals.emplace_back(o.normals[pn], o.normals[pn + 1], o.normals[pn + 2]);
    if (all_uvs_) mesh_.uvs.emplace_back(o.uvs[pt], o.uvs[pt + 1]);
    if (has_colors_) mesh_.colors.push_back({o.colors[pv], o.colors[pv + 1], o.colors[pv + 2], 1.0f});
    return *slot;
  }

  static constexpr std::uint32_t kNoVertex = 0xffffffffu;
  static constexpr std::uint32_t kMaxPolygonCorners = 255;

  const ObjData& obj_;
  std::size_t positions_, normals_, uvs_;
  bool has_colors_;
  std::size_t material_count_;
  std::string source_;
  bool all_normals_ = true, all_uvs_ = true;
  std::unordered_map<CornerKey, std::uint32_t, CornerKeyHash> index_;
  std::vector<std::uint32_t> by_position_;
  std::vector<std::int32_t> face_materials_;
  FaceNumbering faces_;
  Mesh mesh_;
};

std::vector<Material> convert_materials(const std::vector<tinyobj::material_t>& in, const ReferencePolicy& policy,
                                        const LoadOptions& options, const std::string& source) {
  std::vector<Material> out;
  out.reserve(in.size());
  for (const tinyobj::material_t& m : in) {
    Material mat;
    mat.name = m.name;
    mat.diffuse = {m.diffuse[0], m.diffuse[1], m.diffuse[2], m.dissolve};
    mat.specular = {m.specular[0], m.specular[1], m.specular[2]};
    mat.shininess = m.shininess;
    mat.metallic = std::clamp(m.metallic, 0.0f, 1.0f);
    if (m.roughness > 0.0f || m.metallic > 0.0f) {
      mat.roughness = std::clamp(m.roughness, 0.0f, 1.0f);  // MTL's PBR extension: Pr, Pm
    } else {
      // Blinn-Phong's exponent as a GGX roughness (alpha^2 = 2 / (Ns + 2)); no specular colour means a matte surface.
      const bool matte = mat.specular == glm::vec3(0.0f) || !(m.shininess > 0.0f);
      mat.roughness = matte ? 1.0f : std::clamp(std::sqrt(std::sqrt(2.0f / (m.shininess + 2.0f))), 0.0f, 1.0f);
    }
    mat.emissive = srgb_to_linear(glm::vec3(m.emission[0], m.emission[1], m.emission[2]));
    // The extension's clear coat (Pc, Pcr) and sheen (Ps, a strength: a white sheen of that brightness).
    mat.clearcoat = std::isfinite(m.clearcoat_thickness) ? std::clamp(m.clearcoat_thickness, 0.0f, 1.0f) : 0.0f;
    mat.clearcoat_roughness =
        std::isfinite(m.clearcoat_roughness) ? std::clamp(m.clearcoat_roughness, 0.0f, 1.0f) : 0.0f;
    mat.sheen_color = glm::vec3(std::isfinite(m.sheen) ? std::clamp(m.sheen, 0.0f, 1.0f) : 0.0f);
    mat.sheen_roughness = mat.roughness;
    if (!m.diffuse_texname.empty()) {
      const std::string what = "texture '" + printable(m.diffuse_texname) + "' of material '" + printable(m.name) + "'";
      mat.diffuse_texture = usable_texture(policy, options, m.diffuse_texname, what, source).value_or("");
    }
    out.push_back(std::move(mat));
  }
  return out;
}

}  // namespace

Mesh load_obj(const fs::path& path, std::string_view text, const std::string& source, const LoadOptions& options) {
  const ReferencePolicy policy{path.parent_path(), options.allow_external_files};
  MtlReader mtl(policy, source);
  Mesh mesh;
  bool cloud = false;
  try {
    const ObjData obj = parse_obj(
        text, [&](const std::string& name, std::map<std::string, int>& names) { return mtl(name, names); }, source);
    if (obj.dropped_faces > 0)
      warn(source, "dropped " + std::to_string(obj.dropped_faces) + " face(s) with fewer than 3 corners");
    cloud = obj.face_ends.empty();
    mesh = cloud ? point_cloud(obj) : MeshBuilder(obj, mtl.materials.size(), source).build();
  } catch (const std::bad_alloc&) {
    throw InputError(source, "out of memory while loading");
  }
  if (mesh.indices.empty() && mesh.points.empty())
    throw InputError(source, cloud ? "nothing to draw (no faces and no vertices)" : "no triangles found");
  mesh.materials = convert_materials(mtl.materials, policy, options, source);
  validate(mesh, source);
  return mesh;
}

}  // namespace facet
