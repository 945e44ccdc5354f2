// gltf_animation.hpp - a glTF file's motion: its node tree, skins, animations, and each mesh's skin and morph data.
#pragma once

#include <cstddef>
#include <vector>

#include "facet/model.hpp"
#include "job/io/gltf_accessors.hpp"

namespace facet {

// Every node of the file with its parent and its own transform. Throws InputError for a node listed as the child
// of two nodes, a child that does not exist, or a node that is its own ancestor.
std::vector<ModelNode> read_nodes(const Reader& reader);

// Every skin: its joints and inverse bind matrices (identities where the file gives none). Throws InputError for a
// joint that does not exist, inverse bind matrices that are fewer than the joints or not finite.
std::vector<Skin> read_skins(const Reader& reader);

// Every animation that can be played, in the file's order, named by the file (or "" when unnamed). One whose data
// is malformed (accessors of the wrong type or count, key times that are not finite or do not increase, values that
// are not finite, an unknown interpolation, channels on nodes that do not exist, weights for another number of
// morph targets) is left out with a one-line warning naming it and the problem; a channel on a node given by a
// matrix is dropped with a warning.
std::vector<Animation> read_animations(const Reader& reader);

// A mesh's skinning weights and morph targets, gathered primitive by primitive as the mesh is read.
class DeformationReader {
 public:
  explicit DeformationReader(const Reader& reader) : reader_(reader) {}
  // Begins a mesh (the file's mesh `index`).
  void start(int index);
  // The primitive's JOINTS_n / WEIGHTS_n and morph targets, for its `count` vertices just appended to the mesh;
  // `decoded` when its attributes came from Draco, which holds no skins or targets of facet's reading.
  void primitive(const tinygltf::Primitive& primitive, std::size_t count, bool decoded);
  // The mesh's deformation: weights normalised to sum to 1 (a warning says how many did not), vertices of primitives
  // without weights left unskinned, targets of primitives without them zero. Throws InputError for primitives of
  // different target counts or default weights of another count.
  MeshDeformation finish();

 private:
  static constexpr std::size_t kMostInfluences = 8;  // JOINTS_0 and JOINTS_1
  const Reader& reader_;
  int mesh_ = 0;
  std::size_t vertices_ = 0;
  std::size_t influences_ = 0;         // the most any primitive has
  std::vector<std::uint16_t> joints_;  // kMostInfluences per vertex while reading
  std::vector<float> weights_;
  std::vector<MorphTarget> targets_;
  bool any_normals_ = false, any_tangents_ = false;
};

}  // namespace facet
