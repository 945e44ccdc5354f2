// flat.hpp - FlatShader: lit per pixel with one normal per face, so a face under directional light is one colour.
#pragma once

#include "facet/renderer.hpp"
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

  // fragment() for 16 pixels at once, the same operations in the same order, so both give identical images: each
  // lane's face normal times normal_from_object, summed as glm's matrix product sums, then normalised.
  template <class L>
  FACET_LANES_INLINE simd::ColorT<L> fragment_lanes(const FragmentLanes<Varyings, L>& f) const {
    using namespace simd;
    FACET_LANE_TYPES(L);
    alignas(kLaneAlign) float x[kLanes], y[kLanes], z[kLanes];
    for (int k = 0; k < kLanes; ++k) {
      const glm::vec3 face = face_normals[f.primitive[k]];
      x[k] = face.x, y[k] = face.y, z[k] = face.z;
    }
    const Vec3 o{load<Float>(x), load<Float>(y), load<Float>(z)};
    const glm::mat3& m = transforms.normal_from_object;
    Vec3 n = normalize(Vec3{m[0][0] * o.x + m[1][0] * o.y + m[2][0] * o.z, m[0][1] * o.x + m[1][1] * o.y + m[2][1] * o.z,
                            m[0][2] * o.x + m[1][2] * o.y + m[2][2] * o.z});
    const Mask back = back_lanes(f.front_facing);
    n = Vec3{select(back, -n.x, n.x), select(back, -n.y, n.y), select(back, -n.z, n.z)};
    return shade_lanes(albedo_lanes(f), n, f.get(&Varyings::world));
  }
};

}  // namespace facet

// The library compiles these pipelines once (src/scene/shaders/); programs link those instances.
FACET_EXTERN_SHADER(facet::FlatShader);
