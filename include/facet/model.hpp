// model.hpp - a model file's contents: meshes in their own coordinates, the instances placing them, and cameras.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "facet/mesh.hpp"

namespace facet {

// One placement of a mesh in the world: a glTF node with a mesh, or an Assimp node's mesh.
struct ModelInstance {
  std::uint32_t mesh = 0;  // index into Model::meshes
  glm::mat4 world_from_object{1.0f};
  // The file's node: its index in a glTF file's `nodes`, or an Assimp node's place in a depth-first walk of the
  // scene's node tree; 0 for the formats without nodes (OBJ, PLY, STL). Never kNoSurface.
  std::uint32_t id = 0;
};

// What every reader fills, whatever the format: each mesh once, in its own (object) coordinates, with its own
// materials and face_ids (Mesh::instance_ids, cameras and lights empty); the instances that place meshes in the
// world, in the file's scene order (a mesh may be placed by several, or by none); and the cameras and lights the
// scene places.
//
//   facet::Model model = facet::read_model("scene.glb");
//   for (const facet::ModelInstance& i : model.instances)
//     scene.add({std::make_shared<facet::Mesh>(model.meshes[i.mesh]), i.world_from_object});
struct Model {
  std::vector<Mesh> meshes;
  std::vector<ModelInstance> instances;
  std::vector<ModelCamera> cameras;  // world_from_camera in world space, in the order the scene places them
  std::vector<Light> lights;         // world space, in the order the scene places them (glTF KHR_lights_punctual)
};

// The whole model as one mesh in world space: every instance's mesh, in instance order, positions transformed,
// normals by the inverse transpose (renormalised), and the corners of a mirroring instance swapped so its
// triangles stay front-facing. Mesh::instance_ids holds each triangle's ModelInstance::id (left empty when all are
// 0) and Mesh::face_ids its face in its own mesh; materials equal in every field (textures by identity) become
// one; normals are kept only when every placed mesh has them, uvs and colours when any has them (others get
// (0, 0) and white). Moves instead of copying when the model is one mesh placed once, untransformed. Throws
// InputError(source, ...) when the model places no triangle or expands to more than kMaxModelVertices vertices.
Mesh flatten(Model model, const std::string& source);

// The most vertices a model may expand to once every instance is placed (2^27, 6 GiB of vertex attributes).
inline constexpr std::size_t kMaxModelVertices = std::size_t{1} << 27;

}  // namespace facet
