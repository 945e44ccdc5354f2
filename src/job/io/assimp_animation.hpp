// assimp_animation.hpp - what moves in an Assimp scene: its node tree, its meshes' bones, its node animations.
#pragma once

#include <assimp/scene.h>

#include <cstdint>
#include <string>
#include <vector>

#include "facet/model.hpp"

namespace facet {

// Fills out's nodes (`walked`, in the order the reader numbered them, with each one's parent's number, -1 for the
// root), the skins and deformations of its meshes' bones (`slots`: per aiMesh its index in out.meshes, or past
// them for a mesh without triangles; a vertex keeps its 8 heaviest bones, weights normalised with a warning when
// they do not sum to 1), each instance's skin, and every animation's node channels (Assimp's ticks turned to
// seconds: 25 a second when the file gives no rate). An animation whose keys are malformed is left out with a
// warning naming it; a bone that names no node is refused. Morph targets and their animations are not read.
void read_assimp_motion(const aiScene& scene, const std::vector<const aiNode*>& walked,
                        const std::vector<std::int32_t>& parents, const std::vector<std::uint32_t>& slots,
                        Model& out, const std::string& source);

}  // namespace facet
