// mesh_vertex.hpp - the vertex record the stock mesh shaders read, and the per-object matrices they share.
#pragma once

#include <glm/glm.hpp>

namespace facet {

// One vertex of a prepared mesh: every attribute is present (the Scene fills missing ones with defaults).
struct MeshVertex {
  glm::vec3 position{0};
  glm::vec3 normal{0, 0, 1};
  glm::vec2 uv{0};
  glm::vec4 color{1};
  glm::vec2 uv1{0};  // the second texture coordinate set, read by the physically based shading only
  // The normal map's tangent (Mesh::tangents: xyz, w the bitangent's sign), zero where the mesh has none; read by
  // the physically based shading of normal-mapped meshes with tangents only.
  glm::vec4 tangent{0};
};

// The matrices a mesh shader needs for one instance, computed once per draw rather than per vertex.
struct ObjectTransforms {
  glm::mat4 clip_from_object{1.0f};
  glm::mat4 world_from_object{1.0f};
  glm::mat3 normal_from_object{1.0f};  // inverse transpose of world_from_object's 3x3: keeps normals
                                       // perpendicular to surfaces under non-uniform scale
  // world_from_object mirrors (negative determinant): the object's counter-clockwise front faces reach the screen
  // clockwise, so Fragment::front_facing is false on them.
  bool mirrored = false;

  static ObjectTransforms make(const glm::mat4& clip_from_world, const glm::mat4& world_from_object) {
    const glm::mat3 linear(world_from_object);
    return {clip_from_world * world_from_object, world_from_object, glm::transpose(glm::inverse(linear)),
            glm::determinant(linear) < 0.0f};
  }
  // Whether a fragment is on the object's front side.
  bool front_side(bool front_facing) const { return front_facing != mirrored; }
};

}  // namespace facet
