// model.cpp - flatten(): a model's instances placed into one world-space mesh.
#include "facet/model.hpp"

#include <cmath>
#include <string>
#include <utility>

#include "facet/error.hpp"
#include "facet/splats.hpp"

namespace facet {

namespace {

bool same_material(const Material& a, const Material& b) {
  const auto same_sampler = [](const std::optional<Sampler>& x, const std::optional<Sampler>& y) {
    if (x.has_value() != y.has_value()) return false;
    return !x || (x->filter == y->filter && x->wrap_u == y->wrap_u && x->wrap_v == y->wrap_v);
  };
  return a.name == b.name && a.diffuse == b.diffuse && a.specular == b.specular && a.shininess == b.shininess &&
         a.diffuse_texture == b.diffuse_texture && a.diffuse_map == b.diffuse_map &&
         same_sampler(a.sampler, b.sampler) && a.unlit == b.unlit && a.normal_map == b.normal_map &&
         a.normal_scale == b.normal_scale && a.alpha_mode == b.alpha_mode && a.alpha_cutoff == b.alpha_cutoff &&
         a.double_sided == b.double_sided && a.metallic == b.metallic && a.roughness == b.roughness &&
         a.metallic_roughness_map == b.metallic_roughness_map && a.emissive == b.emissive &&
         a.emissive_map == b.emissive_map && a.occlusion_map == b.occlusion_map &&
         a.occlusion_strength == b.occlusion_strength;
}

// The index of an equal material in `materials`, appending it if there is none. Models have few materials, and
// each mesh's are looked up once, so a linear search serves.
std::int32_t material_index(std::vector<Material>& materials, const Material& m) {
  for (std::size_t i = 0; i < materials.size(); ++i)
    if (same_material(materials[i], m)) return static_cast<std::int32_t>(i);
  materials.push_back(m);
  return static_cast<std::int32_t>(materials.size() - 1);
}

bool is_identity(const glm::mat4& m) { return m == glm::mat4(1.0f); }

}  // namespace

Mesh flatten(Model model, const std::string& source) {
  std::size_t vertices = 0, triangles = 0, points = 0, splats = 0;
  bool all_normals = true, any_uvs = false, any_uvs1 = false, any_tangents = false, any_colors = false;
  bool any_face_colors = false, all_intensities = true;
  bool any_ids = false;
  for (const ModelInstance& instance : model.instances) {
    if (instance.mesh >= model.meshes.size())
      throw InputError(source, "instance " + std::to_string(instance.id) + " places mesh " +
                                   std::to_string(instance.mesh) + ", which does not exist");
    const Mesh& mesh = model.meshes[instance.mesh];
    if (mesh.vertex_count() > kMaxModelVertices - vertices)
      throw InputError(source, "the model expands to more than 2^27 vertices");
    vertices += mesh.vertex_count();
    triangles += mesh.triangle_count();
    points += mesh.point_count();
    splats += mesh.splats ? mesh.splats->size() : 0;
    all_normals = all_normals && !mesh.normals.empty();
    any_uvs = any_uvs || !mesh.uvs.empty();
    any_uvs1 = any_uvs1 || !mesh.uvs1.empty();
    any_tangents = any_tangents || !mesh.tangents.empty();
    any_colors = any_colors || !mesh.colors.empty();
    all_intensities = all_intensities && !mesh.intensities.empty();
    any_face_colors = any_face_colors || !mesh.face_colors.empty();
    any_ids = any_ids || instance.id != 0;
  }
  if (triangles == 0 && points == 0 && splats == 0)
    throw InputError(source, "the model places no triangles and no points");

  // One mesh placed once, as it is: the common case of every single-mesh format, moved rather than copied.
  if (model.instances.size() == 1 && is_identity(model.instances[0].world_from_object) && !any_ids) {
    Mesh out = std::move(model.meshes[model.instances[0].mesh]);
    out.cameras = std::move(model.cameras);
    out.lights = std::move(model.lights);
    return out;
  }

  // Splats are placed by Scene instances, not merged: only a model of one mesh, placed once as it is, has them.
  if (splats > 0) throw InputError(source, "Gaussian splats in a model of several placed meshes are not read");
  Mesh out;
  out.positions.reserve(vertices);
  if (all_normals) out.normals.reserve(vertices);
  if (any_uvs) out.uvs.reserve(vertices);
  if (any_uvs1) out.uvs1.reserve(vertices);
  // Tangents only beside normals (glTF ignores them on a mesh without normals).
  any_tangents = any_tangents && all_normals;
  if (any_tangents) out.tangents.reserve(vertices);
  if (any_colors) out.colors.reserve(vertices);
  out.indices.reserve(3 * triangles);
  out.points.reserve(points);
  out.face_ids.reserve(triangles);
  if (any_ids) out.instance_ids.reserve(triangles);
  bool any_materials = false;
  for (const Mesh& mesh : model.meshes) any_materials = any_materials || !mesh.face_materials.empty();
  if (any_materials) out.face_materials.reserve(triangles);

  // Per mesh, its materials' indices among the flattened mesh's, found once.
  std::vector<std::vector<std::int32_t>> material_map(model.meshes.size());
  std::vector<bool> mapped(model.meshes.size(), false);
  for (const ModelInstance& instance : model.instances) {
    const Mesh& mesh = model.meshes[instance.mesh];
    std::vector<std::int32_t>& materials = material_map[instance.mesh];
    if (!mapped[instance.mesh]) {
      for (const Material& m : mesh.materials) materials.push_back(material_index(out.materials, m));
      mapped[instance.mesh] = true;
    }
    const glm::mat4& world = instance.world_from_object;
    const glm::mat3 normal_from_object = glm::transpose(glm::inverse(glm::mat3(world)));
    // A mirroring placement turns the bitangent cross(n, t) around relative to the mirrored texture axes.
    const float handedness = glm::determinant(glm::mat3(world)) < 0.0f ? -1.0f : 1.0f;
    const auto base = static_cast<std::uint32_t>(out.positions.size());
    for (const glm::vec3& p : mesh.positions) out.positions.push_back(glm::vec3(world * glm::vec4(p, 1.0f)));
    if (all_normals)
      for (const glm::vec3& n : mesh.normals) {
        const glm::vec3 v = normal_from_object * n;
        const float length = glm::length(v);
        out.normals.push_back(std::isfinite(length) && length > 0.0f ? v / length : glm::vec3(0, 0, 1));
      }
    if (any_uvs) {
      if (mesh.uvs.empty()) out.uvs.resize(out.positions.size(), glm::vec2(0.0f));
      else out.uvs.insert(out.uvs.end(), mesh.uvs.begin(), mesh.uvs.end());
    }
    if (any_uvs1) {
      if (mesh.uvs1.empty()) out.uvs1.resize(out.positions.size(), glm::vec2(0.0f));
      else out.uvs1.insert(out.uvs1.end(), mesh.uvs1.begin(), mesh.uvs1.end());
    }
    if (any_tangents) {
      if (mesh.tangents.empty()) out.tangents.resize(out.positions.size(), glm::vec4(0.0f));
      for (const glm::vec4& t : mesh.tangents) {
        const glm::vec3 v = glm::mat3(world) * glm::vec3(t);
        const float length = glm::length(v);
        out.tangents.push_back(std::isfinite(length) && length > 0.0f ? glm::vec4(v / length, t.w * handedness)
                                                                      : glm::vec4(0.0f));
      }
    }
    if (any_colors) {
      if (mesh.colors.empty()) out.colors.resize(out.positions.size(), glm::vec4(1.0f));
      else out.colors.insert(out.colors.end(), mesh.colors.begin(), mesh.colors.end());
    }
    // Intensities are the file's own scale: kept only when every mesh has them.
    if (all_intensities) out.intensities.insert(out.intensities.end(), mesh.intensities.begin(), mesh.intensities.end());
    if (any_face_colors) {
      if (mesh.face_colors.empty())
        out.face_colors.resize(out.face_colors.size() + mesh.triangle_count(), glm::vec4(1.0f));
      else out.face_colors.insert(out.face_colors.end(), mesh.face_colors.begin(), mesh.face_colors.end());
    }
    for (const std::uint32_t v : mesh.points) out.points.push_back(base + v);
    // A mirroring transform turns counter-clockwise triangles clockwise; swapping two corners restores the front.
    const bool mirrored = glm::determinant(glm::mat3(world)) < 0.0f;
    for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
      const std::uint32_t* c = &mesh.indices[3 * t];
      out.indices.insert(out.indices.end(), {base + c[0], base + c[mirrored ? 2 : 1], base + c[mirrored ? 1 : 2]});
      out.face_ids.push_back(mesh.face_id(t));
      if (any_ids) out.instance_ids.push_back(instance.id);
      if (any_materials) {
        const std::int32_t m = mesh.face_materials.empty() ? -1 : mesh.face_materials[t];
        out.face_materials.push_back(m < 0 ? -1 : materials[static_cast<std::size_t>(m)]);
      }
    }
  }
  out.cameras = std::move(model.cameras);
  out.lights = std::move(model.lights);
  validate(out, source);
  return out;
}

}  // namespace facet
