// flat.hpp - FlatShader: lit per pixel with one normal per face, so a face under directional light is one colour.
#pragma once

#include <cstdint>

#include "facet/shaders/lit.hpp"

namespace facet {

struct FlatShader : LitUniforms {
  struct Varyings {
    glm::vec3 world;
    glm::vec4 color;
    glm::vec2 uv;
  };

  // Object-space normal of each triangle of the draw, indexed by Fragment::primitive; must not be null.
  const glm::vec3* face_normals = nullptr;

  VertexOut<Varyings> vertex(const Vertex& v) const {
    const glm::vec4 p(v.position, 1.0f);
    return {transforms.clip_from_object * p, {glm::vec3(transforms.world_from_object * p), v.color, v.uv}};
  }
  // Back faces are lit with the normal reversed (two-sided lighting).
  glm::vec4 fragment(const Fragment<Varyings>& f) const {
    const glm::vec3 n = glm::normalize(transforms.normal_from_object * face_normals[f.primitive]);
    return shade(albedo(f), transforms.front_side(f.front_facing) ? n : -n, f.varyings.world);
  }

  // fragment() for 16 pixels at once, the same operations in the same order, so both give identical images. Each
  // lane's face normal is transformed as fragment() does it, once per run of lanes on the same triangle.
  FACET_LANES_INLINE simd::Color fragment_lanes(const FragmentLanes<Varyings>& f) const {
    using namespace simd;
    Vec3 n{};
    std::uint32_t last = f.primitive[0];
    glm::vec3 face = glm::normalize(transforms.normal_from_object * face_normals[last]);
    for (int k = 0; k < kLanes; ++k) {
      if (f.primitive[k] != last) {
        last = f.primitive[k];
        face = glm::normalize(transforms.normal_from_object * face_normals[last]);
      }
      n.x[k] = face.x, n.y[k] = face.y, n.z[k] = face.z;
    }
    const Mask back = back_lanes(f.front_facing);
    n = Vec3{select(back, -n.x, n.x), select(back, -n.y, n.y), select(back, -n.z, n.z)};
    return shade_lanes(albedo_lanes(f), n, f.get(&Varyings::world));
  }
};

}  // namespace facet
