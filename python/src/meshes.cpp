// meshes.cpp - the Python module's meshes (from arrays or files) and scenes of placed meshes.
#include "meshes.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <utility>

#include "facet/color.hpp"
#include "facet/error.hpp"
#include "facet/model_io.hpp"
#include "facet/texture.hpp"
#include "materials.hpp"

namespace facet::python {

MeshCore MeshCore::from_arrays(py::handle positions, py::handle faces, py::handle normals, py::handle uvs,
                               py::handle colors, py::handle texture, py::handle material) {
  Mesh mesh;
  mesh.positions = finite_rows<3>(positions, "positions");
  if (mesh.positions.empty()) value_error("positions: the mesh has no vertices");
  if (mesh.positions.size() > kMaxModelVertices) value_error("positions: more than 2^27 vertices");
  if (faces.is_none()) {
    // A point cloud: every position a point.
    mesh.points_at_every_vertex();
  } else {
    const auto f = checked_array<std::int64_t>(faces, "faces", "iu", 2, {3});
    if (f.shape(0) == 0) value_error("faces: the mesh has no triangles");
    const auto n = static_cast<std::int64_t>(mesh.positions.size());
    mesh.indices.reserve(static_cast<std::size_t>(f.size()));
    for (py::ssize_t i = 0; i < f.size(); ++i) {
      const std::int64_t index = f.data()[i];
      if (index < 0 || index >= n)
        value_error("faces: row " + std::to_string(i / 3) + " refers to vertex " + std::to_string(index) + " of " +
                    std::to_string(n));
      mesh.indices.push_back(static_cast<std::uint32_t>(index));
    }
  }
  const auto per_vertex = [&](std::size_t size, const char* name) {
    if (size != mesh.positions.size())
      value_error(std::string(name) + ": " + std::to_string(size) + " rows for " +
                  std::to_string(mesh.positions.size()) + " vertices");
  };
  if (!normals.is_none()) {
    mesh.normals = finite_rows<3>(normals, "normals");
    per_vertex(mesh.normals.size(), "normals");
  }
  if (!uvs.is_none()) {
    mesh.uvs = finite_rows<2>(uvs, "uvs");
    per_vertex(mesh.uvs.size(), "uvs");
  }
  if (!colors.is_none()) {
    const py::array a = py::array::ensure(colors);
    const bool bytes = a && a.dtype().kind() == 'u' && a.dtype().itemsize() == 1;
    const auto c = checked_array<float>(colors, "colors", "fiu", 2, {3, 4});
    per_vertex(static_cast<std::size_t>(c.shape(0)), "colors");
    const py::ssize_t k = c.shape(1);
    for (py::ssize_t i = 0; i < c.shape(0); ++i) {
      glm::vec4 rgba(1.0f);
      for (py::ssize_t j = 0; j < k; ++j) {
        const float v = c.at(i, j) / (bytes ? 255.0f : 1.0f);
        if (!(v >= 0.0f && v <= 1.0f)) value_error("colors: row " + std::to_string(i) + " is outside 0..1");
        rgba[static_cast<int>(j)] = v;
      }
      mesh.colors.push_back(rgba);
    }
  }
  // Every triangle gets a material, so that it is culled as its material's sides say (make_sides_explicit).
  Material look = material.is_none() ? default_material() : material_of(material, !mesh.uvs.empty());
  // pyrender's COLOR_0 is linear and multiplies the lit colour; Mesh keeps vertex colours as displayed.
  if (look.pyrender_lighting)
    for (glm::vec4& c : mesh.colors) c = linear_to_srgb(c);
  if (!texture.is_none()) {
    if (mesh.uvs.empty()) value_error("texture: a textured mesh needs uvs");
    if (material.is_none()) {
      look.name = "texture";
      look.specular = glm::vec3(0.0f);  // as textured meshes have always been drawn
    }
    // The material's own baseColorTexture, when it has one, is the one drawn.
    if (!look.diffuse_map) look.diffuse_map = texture_of(texture, "texture", TexelEncoding::srgb);
  }
  mesh.materials.push_back(std::move(look));
  mesh.face_materials.assign(mesh.triangle_count(), 0);
  if (!mesh.points.empty()) mesh.point_material = 0;
  try {
    validate(mesh, "mesh");
  } catch (const InputError& e) {
    value_error(e.what());
  }
  return MeshCore{std::make_shared<const Mesh>(std::move(mesh))};
}

py::array MeshCore::bounds() const {
  const Bounds b = facet::bounds(*mesh);
  return py::array_t<double>({2, 3}, std::vector<double>{b.min.x, b.min.y, b.min.z, b.max.x, b.max.y, b.max.z}.data());
}

void SceneCore::sync(py::list instances) {
  std::vector<Instance> wanted;
  std::vector<std::uint32_t> ids;
  wanted.reserve(instances.size());
  ids.reserve(instances.size());
  for (const py::handle item : instances) {
    const auto t = item.cast<py::tuple>();
    if (t.size() != 4) value_error("scene: expected (mesh, pose, node id, wireframe) for each instance");
    wanted.push_back(Instance{t[0].cast<const MeshCore&>().mesh, matrix4(t[1], "pose"), t[3].cast<bool>()});
    ids.push_back(t[2].cast<std::uint32_t>());
  }
  std::unique_lock lock(mutex);
  const std::vector<Instance>& have = scene.instances();
  const bool same_meshes =
      have.size() == wanted.size() &&
      std::equal(have.begin(), have.end(), wanted.begin(),
                 [](const Instance& a, const Instance& b) { return a.mesh == b.mesh && a.wireframe == b.wireframe; });
  if (same_meshes) {
    for (std::size_t i = 0; i < wanted.size(); ++i)
      if (have[i].world_from_object != wanted[i].world_from_object) scene.set_transform(i, wanted[i].world_from_object);
  } else {
    // The new instances go in before the old ones leave, so that a mesh in both keeps its prepared data.
    const std::size_t old = have.size();
    for (Instance& instance : wanted) scene.add(std::move(instance));
    for (std::size_t i = old; i-- > 0;) scene.remove(i);
  }
  node_ids = std::move(ids);
}

MeshCore load_mesh_file(const std::string& path, const LoadOptions& options) {
  Mesh mesh;
  {
    py::gil_scoped_release released;
    std::string format;
    mesh = load_model(path, format, options);
    make_sides_explicit(mesh, format);
  }
  return MeshCore{std::make_shared<const Mesh>(std::move(mesh))};
}

LoadOptions load_options_of(bool allow_external_files, py::handle max_triangles, py::handle max_points,
                            py::handle max_texture_size) {
  constexpr auto kMost = static_cast<long long>(kMostMaxTriangles);
  constexpr auto kMostPoints = static_cast<long long>(kMostMaxPoints);
  return LoadOptions{
      .allow_external_files = allow_external_files,
      .max_triangles = static_cast<std::uint64_t>(integer_in(max_triangles, "max_triangles", 1, kMost)),
      .max_points = static_cast<std::uint64_t>(integer_in(max_points, "max_points", 1, kMostPoints)),
      .max_texture_size = static_cast<int>(integer_in(max_texture_size, "max_texture_size", 1, kMaxTextureSize))};
}

namespace {

py::array_t<double> matrix_of(const glm::mat4& m) {
  py::array_t<double> out({4, 4});
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) out.mutable_at(r, c) = m[c][r];
  return out;
}

// Whether a skin or morph targets move the instance's vertices at some moment.
bool deformed(const Model& model, const ModelInstance& instance) {
  if (model.deformations.empty()) return false;
  const MeshDeformation& d = model.deformations[instance.mesh];
  return !d.morph_targets.empty() || (instance.skin >= 0 && d.influences > 0);
}

}  // namespace

MotionCore::MotionCore(Model model, std::string source) : model_(std::move(model)), source_(std::move(source)) {}

py::list MotionCore::animations() const {
  py::list out;
  for (const Animation& a : model_.animations) out.append(py::make_tuple(a.name, a.duration()));
  return out;
}

py::list MotionCore::pose(std::optional<std::string> animation, double seconds) {
  if (!std::isfinite(seconds)) value_error("time: must be a finite number of seconds");
  const std::size_t clip = animation_named(model_.animations, animation.value_or(""), source_);
  const Model* posed = nullptr;
  {
    py::gil_scoped_release released;
    posed = &poser_(model_, clip, seconds, source_);
  }
  py::list out;
  for (std::size_t k = 0; k < posed->instances.size(); ++k) {
    const ModelInstance& i = posed->instances[k];
    py::object core = py::none();
    if (deformed(model_, model_.instances[k]))
      core = py::cast(MeshCore{std::make_shared<const Mesh>(posed->meshes[i.mesh])});
    out.append(py::make_tuple(matrix_of(i.world_from_object), core));
  }
  return out;
}

py::tuple read_model_file(const std::string& path, const LoadOptions& options) {
  Model model;
  std::string format;
  std::vector<bool> moving;
  std::unique_ptr<MotionCore> motion;
  {
    py::gil_scoped_release released;
    model = read_model(path, format, options);
    for (Mesh& mesh : model.meshes) make_sides_explicit(mesh, format);
    if (!model.animations.empty() || !model.deformations.empty()) {
      for (const ModelInstance& i : model.instances) moving.push_back(deformed(model, i));
      motion = std::make_unique<MotionCore>(model, path);
      model = at_rest(std::move(model), path, options.threads);
    }
  }
  py::list meshes, instances, cameras;
  for (Mesh& mesh : model.meshes) meshes.append(MeshCore{std::make_shared<const Mesh>(std::move(mesh))});
  const auto matrix = [](const glm::mat4& m) { return matrix_of(m); };
  for (std::size_t k = 0; k < model.instances.size(); ++k) {
    const ModelInstance& i = model.instances[k];
    instances.append(py::make_tuple(i.mesh, matrix(i.world_from_object), i.id, !moving.empty() && moving[k]));
  }
  for (const ModelCamera& c : model.cameras) {
    py::dict camera;
    camera["name"] = c.name;
    camera["perspective"] = c.perspective;
    camera["yfov"] = c.yfov_radians;
    camera["xmag"] = c.magnification.x;
    camera["ymag"] = c.magnification.y;
    camera["znear"] = c.znear;
    camera["zfar"] = c.zfar ? py::cast(*c.zfar) : py::none();
    camera["pose"] = matrix(c.world_from_camera);
    cameras.append(camera);
  }
  return py::make_tuple(meshes, instances, cameras, motion ? py::cast(std::move(motion)) : py::none());
}

}  // namespace facet::python
