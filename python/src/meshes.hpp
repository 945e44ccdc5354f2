// meshes.hpp - the Python module's meshes and scenes: facet meshes shared between Python objects and scenes.
#pragma once

#include <cstdint>
#include <memory>
#include <mutex>
#include <shared_mutex>
#include <string>
#include <vector>

#include "arrays.hpp"
#include "facet/mesh.hpp"
#include "facet/model.hpp"
#include "facet/model_io.hpp"
#include "facet/scene.hpp"

namespace facet::python {

// A mesh as Python holds it: immutable once made, so scenes and renderers share it without copies.
struct MeshCore {
  std::shared_ptr<const Mesh> mesh;

  // From numpy arrays: positions N x 3, faces F x 3 (integers), and optionally normals N x 3, uvs N x 2, colours
  // N x 3 or N x 4 (floats in 0..1 or uint8), texture H x W (x 3 or 4), top row first (uint8, or floats in 0..1),
  // and a material (a MetallicRoughnessMaterial's _core_dict(); materials.hpp). Raises ValueError for a wrong
  // shape or dtype, a non-finite value or an index out of range.
  static MeshCore from_arrays(py::handle positions, py::handle faces, py::handle normals, py::handle uvs,
                              py::handle colors, py::handle texture, py::handle material);
  py::array bounds() const;  // 2 x 3: min and max corner
};

// The meshes a Python scene places, as a facet::Scene, with each instance's node id for the id buffer. Renders
// share it (a shared lock); changes take it alone.
struct SceneCore {
  Scene scene;
  std::vector<std::uint32_t> node_ids;
  mutable std::shared_mutex mutex;

  // Makes the scene's instances those of `instances`, a list of (MeshCore, 4x4 world pose, node id, wireframe),
  // in order. Meshes placed before and after keep their prepared data (Scene::add prepares a mesh it has not
  // seen), so a frame after a change of poses or nodes prepares only the meshes that are new.
  void sync(py::list instances);
};

// The LoadOptions of the Python keywords allow_external_files, max_triangles, max_points and max_texture_size, in the
// ranges `facet render` accepts for its flags; raises ValueError outside them.
LoadOptions load_options_of(bool allow_external_files, py::handle max_triangles, py::handle max_points,
                            py::handle max_texture_size);

// load_model for Python: the whole file as one world-space mesh, its sides made explicit (materials.hpp).
MeshCore load_mesh_file(const std::string& path, const LoadOptions& options);

// A model file's motion, kept for Scene.set_time: the model as read (its nodes, skins, morph targets and
// animations) and a Poser that poses it frame after frame.
class MotionCore {
 public:
  MotionCore(Model model, std::string source);
  // (name, duration in seconds) of each animation, in the file's order.
  py::list animations() const;
  // The model `seconds` into the animation named (its name or index; None: the first): per instance, in the
  // file's order, (4x4 world pose, MeshCore of its deformed mesh, or None for an instance whose mesh nothing
  // deforms). Raises LoadError for an animation the file does not have (or none), ValueError for a time that is not
  // finite.
  py::list pose(std::optional<std::string> animation, double seconds);

 private:
  Model model_;
  std::string source_;
  Poser poser_;
};

// read_model for Python, the meshes' sides made explicit and skins and morph targets at rest: (meshes,
// [(mesh index, 4x4 pose, node id, deformed)], [camera dicts], MotionCore or None). An instance that a skin or
// morph targets deform has a mesh of its own, which MotionCore::pose replaces; the MotionCore is None for a file
// with neither animations nor deformations.
py::tuple read_model_file(const std::string& path, const LoadOptions& options);

}  // namespace facet::python
