// model.hpp - a model file's contents: meshes in their own coordinates, the instances placing them, and cameras.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "facet/animation.hpp"
#include "facet/mesh.hpp"

namespace facet {

// One placement of a mesh in the world: a glTF node with a mesh, or an Assimp node's mesh.
struct ModelInstance {
  std::uint32_t mesh = 0;  // index into Model::meshes
  glm::mat4 world_from_object{1.0f};
  // The file's node: its index in a glTF file's `nodes`, or an Assimp node's place in a depth-first walk of the
  // scene's node tree; 0 for the formats without nodes (OBJ, PLY, STL). Never kNoSurface.
  std::uint32_t id = 0;
  // The node that places it, an index into Model::nodes, whose pose moves it; -1: world_from_object is fixed.
  std::int32_t node = -1;
  // The skin that deforms it, an index into Model::skins; -1: none. A skinned mesh is placed by its joints, not by
  // its node (glTF).
  std::int32_t skin = -1;
};

// A node of the file's hierarchy as it stands unanimated: its parent and its transform, either a matrix or
// translation, rotation and scale (the local transform is then T * R * S), which animations replace.
struct ModelNode {
  std::string name;
  std::int32_t parent = -1;           // an index into Model::nodes; -1 for a root
  std::optional<glm::mat4> matrix{};  // set: the node's transform, which no animation may drive
  glm::vec3 translation{0.0f};
  glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};
  glm::vec3 scale{1.0f};
  std::vector<float> weights{};  // its mesh's morph target weights; empty: the mesh's defaults
};

// A skeleton that deforms the meshes placed with it: its joints (indices into Model::nodes) and for each the
// inverse bind matrix that takes the mesh's coordinates into that joint's.
struct Skin {
  std::string name;
  std::vector<std::uint32_t> joints;
  std::vector<glm::mat4> inverse_bind_matrices;  // one per joint
};

// One morph target: what it adds to each vertex at weight 1. Each array is empty or has one entry per vertex.
struct MorphTarget {
  std::vector<glm::vec3> positions, normals, tangents;
};

// What moves a mesh's vertices when it is posed: morph targets, blended by weights (the mesh's defaults, or its
// node's), and skinning weights: `influences` pairs of a joint (an index into its skin's joints) and a weight per
// vertex, each vertex's weights summing to 1 (or all 0: the vertex then follows its node, unskinned).
struct MeshDeformation {
  std::vector<MorphTarget> morph_targets;
  std::vector<float> default_weights;  // one per morph target
  std::uint32_t influences = 0;        // 0: not skinned
  std::vector<std::uint16_t> joints;   // influences per vertex
  std::vector<float> weights;          // influences per vertex
  bool empty() const { return morph_targets.empty() && influences == 0; }
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
  // The motion a file holds (glTF): its nodes, skins and animations, and each mesh's deformation (empty, or one
  // per mesh). Instances of meshes that deform or nodes that move are placed as they stand unanimated; pose()
  // moves them.
  std::vector<ModelNode> nodes;
  std::vector<Skin> skins;
  std::vector<Animation> animations;
  std::vector<MeshDeformation> deformations;
  // The node that places each camera and each light (indices into nodes, parallel to cameras and lights; -1, or
  // empty, where it stays as placed): pose() moves them with their nodes.
  std::vector<std::int32_t> camera_nodes, light_nodes;
};

// A camera's world_from_camera from its node's world transform: the scale taken out of each axis, the rotation and
// position kept, so that the view stays rigid (glTF allows no scale on camera nodes).
glm::mat4 rigid_camera_pose(const glm::mat4& world_from_node);
// Places a light as a node does: a point or spot light at the node's origin, a directional or spot light shining
// down its -Z. False (the light unchanged) when the transform is not finite or flattens that direction.
bool place_light(Light& light, const glm::mat4& world_from_node);

// The whole model as one mesh in world space: every instance's mesh, in instance order, positions transformed,
// normals by the inverse transpose (renormalised), and the corners of a mirroring instance swapped so its
// triangles stay front-facing. Mesh::instance_ids holds each triangle's ModelInstance::id (left empty when all are
// 0) and Mesh::face_ids its face in its own mesh; materials equal in every field (textures by identity) become
// one; normals are kept only when every placed mesh has them, uvs and colours when any has them (others get
// (0, 0) and white). Moves instead of copying when the model is one mesh placed once, untransformed. Throws
// InputError(source, ...) when the model places no triangle or expands to more than kMaxModelVertices vertices.
Mesh flatten(Model model, const std::string& source);

// The model as it stands `seconds` into `animation` (an index into model.animations; nullopt: none, the nodes as
// they are), clamped to the clip: every node's transform, morph weights blended into their meshes, skins applied
// (a skinned instance's mesh comes out in world space, placed by the identity). Meshes that nothing moves are copied
// as they are. The result has neither deformations nor animations; its nodes are the posed ones. `threads` (0: the
// machine's cores) deform large meshes in parts. Throws InputError(source, ...) for a node whose parent does not exist
// or is its own ancestor, an instance's node or skin that does not exist, a skin's joint that does not exist, a
// vertex's joint past its skin's joints, a sampler that validate() refuses, weights of the wrong count;
// std::out_of_range for an animation index past the model's.
Model pose(const Model& model, std::optional<std::size_t> animation, double seconds, const std::string& source,
           int threads = 1);

// The model as a viewer draws it unanimated: pose(model, nullopt, 0) when skins or morph targets deform it, else
// the model itself, moved through untouched. What load_model, `facet info`, the viewer and Python draw at rest.
Model at_rest(Model model, const std::string& source, int threads = 1);

// pose() frame after frame: the posed model's memory and the threads that skin large meshes are kept from one call
// to the next, so that a clip's frames do not each take a model's worth of fresh memory.
//
//   facet::Poser poser(2);
//   for (int k = 0; k < frames; ++k) draw(poser(model, 0, k / 30.0, "walk.glb"));
class Poser {
 public:
  explicit Poser(int threads = 1);  // 0: the machine's cores
  ~Poser();
  Poser(Poser&&) noexcept;
  Poser& operator=(Poser&&) noexcept;
  // What pose(model, animation, seconds, source) returns, valid until the next call; throws as pose() does.
  Model& operator()(const Model& model, std::optional<std::size_t> animation, double seconds,
                    const std::string& source);

 private:
  struct Kept;
  std::unique_ptr<Kept> kept_;
};

// Each node's transform in the world: its parents' composed with its own. Throws as pose() does for a broken
// hierarchy.
std::vector<glm::mat4> world_from_nodes(const std::vector<ModelNode>& nodes, const std::string& source);

// The most vertices a model may expand to once every instance is placed (2^27, 6 GiB of vertex attributes).
inline constexpr std::size_t kMaxModelVertices = std::size_t{1} << 27;

}  // namespace facet
