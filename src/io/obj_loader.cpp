// obj_loader.cpp - load_obj(): Wavefront OBJ + MTL through tinyobjloader, checked, indexed and triangulated.
#include <tiny_obj_loader.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <iostream>
#include <limits>
#include <map>
#include <numeric>
#include <string>
#include <string_view>
#include <unordered_map>

#include "facet/error.hpp"
#include "facet/model_io.hpp"
#include "io/file_util.hpp"
#include "io/loaders.hpp"

namespace facet {

namespace fs = std::filesystem;

namespace {

// Lets tinyobj read the file's bytes in place; an istringstream would copy them.
class ViewBuffer : public std::streambuf {
 public:
  explicit ViewBuffer(FileBytes& text) { setg(text.data(), text.data(), text.data() + text.size()); }
};

// Reads MTL files from the .obj's folder tree (references.hpp). tinyobj's own reader splits its search path at
// ':', which breaks on folders containing one, opens whatever path the file names, and reports a missing file as a
// multi-line warning; this one warns in facet's format.
class MtlReader final : public tinyobj::MaterialReader {
 public:
  MtlReader(ReferencePolicy policy, std::string source) : policy_(std::move(policy)), source_(std::move(source)) {}

  bool operator()(const std::string& name, std::vector<tinyobj::material_t>* materials,
                  std::map<std::string, int>* names, std::string* warnings, std::string* errors) override {
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
    tinyobj::LoadMtl(names, materials, &in, warnings, errors);
    return true;
  }

 private:
  ReferencePolicy policy_;
  std::string source_;
};

// tinyobj reads "nan" and "inf" as 0, so a position that the file spells as non-finite would pass silently;
// find those `v` lines first. (Overflowing numbers do come out infinite and are caught after parsing.)
bool spells_non_finite(std::string_view token) {
  if (!token.empty() && (token[0] == '+' || token[0] == '-')) token.remove_prefix(1);
  std::string head(token.substr(0, 3));
  for (char& c : head) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return head == "nan" || head == "inf";  // also "infinity", "nan(...)"
}

void reject_non_finite_spellings(std::string_view text, const std::string& source) {
  std::size_t line = 0;
  for (std::size_t pos = 0; pos < text.size();) {
    const std::size_t end = std::min(text.find('\n', pos), text.size());
    ++line;
    std::string_view l = text.substr(pos, end - pos);
    pos = end + 1;
    const std::size_t start = l.find_first_not_of(" \t");
    if (start == std::string_view::npos || l.size() < start + 2 || l[start] != 'v' ||
        (l[start + 1] != ' ' && l[start + 1] != '\t'))
      continue;
    l.remove_prefix(start + 2);
    for (int k = 0; k < 3; ++k) {
      const std::size_t from = l.find_first_not_of(" \t\r");
      if (from == std::string_view::npos) break;
      l.remove_prefix(from);
      const std::string_view token = l.substr(0, l.find_first_of(" \t\r"));
      l.remove_prefix(token.size());
      if (spells_non_finite(token))
        throw InputError(source, "non-finite vertex position on line " + std::to_string(line));
    }
  }
}

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

// Builds the indexed mesh from tinyobj's per-face corner lists.
class MeshBuilder {
 public:
  MeshBuilder(const tinyobj::attrib_t& attrib, std::size_t material_count, std::string source)
      : attrib_(attrib),
        positions_(attrib.vertices.size() / 3),
        normals_(attrib.normals.size() / 3),
        uvs_(attrib.texcoords.size() / 2),
        has_colors_(!attrib.colors.empty() && attrib.colors.size() == attrib.vertices.size()),
        material_count_(material_count),
        source_(std::move(source)) {}

  void add_shape(const tinyobj::mesh_t& shape) {
    // num_face_vertices is 8-bit, so a polygon of 256+ corners shows up as a count that no longer adds up.
    const std::size_t listed =
        std::accumulate(shape.num_face_vertices.begin(), shape.num_face_vertices.end(), std::size_t{0});
    if (listed != shape.indices.size())
      throw InputError(source_, "a polygon has more than 255 corners (not supported)");
    std::size_t offset = 0;
    std::vector<std::uint32_t> polygon;
    for (std::size_t f = 0; f < shape.num_face_vertices.size(); ++f) {
      const std::size_t corners = shape.num_face_vertices[f];
      polygon.clear();
      for (std::size_t k = 0; k < corners; ++k) polygon.push_back(vertex_for(shape.indices[offset + k]));
      offset += corners;
      // Faces are numbered as the file lists them, across groups and objects (tinyobj keeps no face of fewer than
      // three corners, so those are not counted).
      if (corners < 3) {
        faces_.drop_face();
        continue;
      }
      const std::size_t before = mesh_.indices.size();
      triangulate_polygon(mesh_.positions, polygon, mesh_.indices);
      faces_.add_face(mesh_, before / 3);
      const int id = f < shape.material_ids.size() ? shape.material_ids[f] : -1;
      const std::int32_t material = (id >= 0 && static_cast<std::size_t>(id) < material_count_) ? id : -1;
      face_materials_.insert(face_materials_.end(), (mesh_.indices.size() - before) / 3, material);
    }
  }

  Mesh finish() {
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

  std::uint32_t vertex_for(const tinyobj::index_t& corner) {
    const int v = corner.vertex_index, vt = corner.texcoord_index, vn = corner.normal_index;
    // tinyobj accepts any index and only warns; an index past the end would read outside its arrays.
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

    const auto& a = attrib_;
    const std::size_t pv = 3 * static_cast<std::size_t>(v);
    const glm::vec3 p(a.vertices[pv], a.vertices[pv + 1], a.vertices[pv + 2]);
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      throw InputError(source_, "non-finite vertex position (vertex " + std::to_string(v + 1) + ")");
    mesh_.positions.push_back(p);
    all_normals_ = all_normals_ && vn >= 0;
    all_uvs_ = all_uvs_ && vt >= 0;
    const std::size_t pn = 3 * static_cast<std::size_t>(std::max(vn, 0)),
                      pt = 2 * static_cast<std::size_t>(std::max(vt, 0));
    mesh_.normals.push_back(vn >= 0 ? glm::vec3(a.normals[pn], a.normals[pn + 1], a.normals[pn + 2]) : glm::vec3(0));
    mesh_.uvs.push_back(vt >= 0 ? glm::vec2(a.texcoords[pt], a.texcoords[pt + 1]) : glm::vec2(0));
    if (has_colors_) mesh_.colors.push_back({a.colors[pv], a.colors[pv + 1], a.colors[pv + 2], 1.0f});
    return *slot;
  }

  static constexpr std::uint32_t kNoVertex = 0xffffffffu;

  const tinyobj::attrib_t& attrib_;
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
    if (!m.diffuse_texname.empty()) {
      const std::string what = "texture '" + printable(m.diffuse_texname) + "' of material '" + printable(m.name) + "'";
      mat.diffuse_texture = usable_texture(policy, options, m.diffuse_texname, what, source).value_or("");
    }
    out.push_back(std::move(mat));
  }
  return out;
}

std::string first_line(const std::string& s) {
  std::string line = s.substr(0, s.find('\n'));
  while (!line.empty() && std::isspace(static_cast<unsigned char>(line.back()))) line.pop_back();
  return printable(line.empty() ? "unknown parse error" : line);
}

// tinyobj's only parse failure reads "Failed parse `f' line(e.g. zero value for face index. line 5.)"; say it in
// facet's words, keeping anything unexpected verbatim.
std::string parse_problem(const std::string& errors) {
  const std::string line = first_line(errors);
  const std::string prefix = "Failed parse `";
  const std::size_t at = line.rfind("line ");
  if (line.rfind(prefix, 0) != 0 || line.size() <= prefix.size() || at == std::string::npos)
    return "cannot parse OBJ: " + line;
  std::string number;
  for (std::size_t i = at + 5; i < line.size() && std::isdigit(static_cast<unsigned char>(line[i])); ++i)
    number += line[i];
  return std::string("malformed '") + line[prefix.size()] + "' element on line " + number +
         " (an index is 0 or not a number)";
}

}  // namespace

Mesh load_obj(const fs::path& path, FileBytes& text, const std::string& source, const LoadOptions& options) {
  reject_non_finite_spellings(text, source);

  const ReferencePolicy policy{path.parent_path(), options.allow_external_files};
  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  std::vector<tinyobj::material_t> materials;
  std::string warnings, errors;
  Mesh mesh;
  try {
    ViewBuffer buffer(text);
    std::istream in(&buffer);
    MtlReader mtl(policy, source);
    // No triangulation in tinyobj: it splits quads along the shorter diagonal, where the reference splits them as
    // (c0 c1 c2), (c0 c2 c3), and its ear clipper trusts the indices. Without fallback colours, attrib.colors
    // stays empty unless every vertex has them.
    if (!tinyobj::LoadObj(&attrib, &shapes, &materials, &warnings, &errors, &in, &mtl, /*triangulate=*/false,
                          /*default_vcols_fallback=*/false))
      throw InputError(source, parse_problem(errors));
    MeshBuilder builder(attrib, materials.size(), source);
    for (const tinyobj::shape_t& shape : shapes) builder.add_shape(shape.mesh);
    mesh = builder.finish();
  } catch (const InputError&) {
    throw;
  } catch (const std::bad_alloc&) {
    throw InputError(source, "out of memory while loading");
  } catch (const std::exception& e) {
    throw InputError(source, "cannot parse OBJ: " + first_line(e.what()));
  }
  if (mesh.indices.empty()) throw InputError(source, "no triangles found");

  std::size_t dropped = 0;
  for (std::size_t at = warnings.find("Degenerated face"); at != std::string::npos;
       at = warnings.find("Degenerated face", at + 1))
    ++dropped;
  if (dropped > 0) warn(source, "dropped " + std::to_string(dropped) + " face(s) with fewer than 3 corners");

  mesh.materials = convert_materials(materials, policy, options, source);
  validate(mesh, source);
  return mesh;
}

}  // namespace facet
