// bench_shader.hpp - the `facet bench` shader: BENCHMARK.md section 7 (textured Lambert + Phong) as a facet Shader.
#pragma once

#include <cmath>

#include <glm/glm.hpp>

#include "facet/fragment_lanes.hpp"
#include "facet/renderer.hpp"
#include "facet/shader.hpp"
#include "facet/texture.hpp"
#include "facet/vertex_lanes.hpp"

namespace facet::bench {

// One vertex as the reference uploads it: position, normal and uv, 32-bit floats.
struct BenchVertex {
  glm::vec3 pos;
  glm::vec3 normal;
  glm::vec2 uv;
};

// Direction to the light, normalised in float32 exactly as glref does before it sets the uniform.
inline glm::vec3 bench_light_direction() {
  const float len = std::sqrt(0.4f * 0.4f + 0.7f * 0.7f + 0.6f * 0.6f);
  return {0.4f / len, 0.7f / len, 0.6f / len};
}

struct BenchShader {
  using Vertex = BenchVertex;
  struct Varyings {
    glm::vec3 world_pos;
    glm::vec3 world_normal;  // not normalised per vertex: the fragment stage normalises the interpolated value
    glm::vec2 uv;
  };
  // No discard, so the pipeline tests depth before shading and hidden fragments cost no texture lookups.
  static constexpr bool may_discard = false;
  // fragment_lanes reads neither primitive nor front_facing: the pipeline need not fill them per lane.
  static constexpr bool lanes_read_primitive = false;

  // Uniforms. clip_from_world = P * V, formed once, like GLSL's `uProj * uView * pw` which multiplies the two
  // matrices before the vector.
  glm::mat4 world_from_object{1.0f};
  glm::mat3 normal_matrix{1.0f};  // upper-left 3x3 of world_from_object (rotation times uniform scale)
  glm::mat4 clip_from_world{1.0f};
  glm::vec3 light_dir = bench_light_direction();
  glm::vec3 eye{0.0f, 0.0f, 3.0f};
  const Texture* texture = nullptr;
  Sampler sampler{Filter::bilinear, Wrap::repeat, Wrap::repeat};

  // Per frame: M(f) and the normal matrix derived from it (outside the per-vertex loop).
  void set_model(const glm::mat4& model) {
    world_from_object = model;
    normal_matrix = glm::mat3(model);
  }

  VertexOut<Varyings> vertex(const Vertex& v) const {
    const glm::vec4 world = world_from_object * glm::vec4(v.pos, 1.0f);
    return {clip_from_world * world, {glm::vec3(world), normal_matrix * v.normal, v.uv}};
  }

  // vertex() for 16 vertices at once, in glm's order: M * v is (m0 x + m1 y) + (m2 z + m3 w) per row, a mat3
  // product m0 x + m1 y + m2 z; w = 1 makes m3 w exactly m3.
  template <class L>
  FACET_LANES_INLINE VertexOutLanes<Varyings, L> vertex_lanes(const VertexLanes<Vertex, L>& v) const {
    FACET_LANE_TYPES(L);
    const Vec3 pos = v.get(&Vertex::pos), normal = v.get(&Vertex::normal);
    const auto transform =
        [](const glm::mat4& m, int row, Float x, Float y, Float z, Float w) __attribute__((always_inline)) {
      return (m[0][row] * x + m[1][row] * y) + (m[2][row] * z + m[3][row] * w);
    };
    const Float one = simd::splat<L>(1.0f);
    Float world[4], clip[4];
    for (int row = 0; row < 4; ++row) world[row] = transform(world_from_object, row, pos.x, pos.y, pos.z, one);
    for (int row = 0; row < 4; ++row)
      clip[row] = transform(clip_from_world, row, world[0], world[1], world[2], world[3]);
    const auto rotate = [&](int row) __attribute__((always_inline)) {
      return normal_matrix[0][row] * normal.x + normal_matrix[1][row] * normal.y + normal_matrix[2][row] * normal.z;
    };
    VertexOutLanes<Varyings, L> out;
    out.clip_x = clip[0], out.clip_y = clip[1], out.clip_z = clip[2], out.clip_w = clip[3];
    out.set(&Varyings::world_pos, Vec3{world[0], world[1], world[2]});
    out.set(&Varyings::world_normal, Vec3{rotate(0), rotate(1), rotate(2)});
    out.set(&Varyings::uv, v.get(&Vertex::uv));
    return out;
  }

  glm::vec4 fragment(const Fragment<Varyings>& f) const {
    const Varyings& in = f.varyings;
    const glm::vec3 n = in.world_normal * (1.0f / std::sqrt(glm::dot(in.world_normal, in.world_normal)));
    const glm::vec3 to_eye = eye - in.world_pos;
    const glm::vec3 v = to_eye * (1.0f / std::sqrt(glm::dot(to_eye, to_eye)));
    const float n_dot_l = glm::dot(n, light_dir);
    const glm::vec3 r = 2.0f * n_dot_l * n - light_dir;  // reflect(-L, N)
    const glm::vec3 albedo = glm::vec3(texture->sample(in.uv, sampler));
    const float diffuse = n_dot_l > 0.0f ? n_dot_l : 0.0f;
    // pow(x, 32) as five squarings: exact enough (a few ulps) and far cheaper than exp2(32 * log2(x)).
    float spec = glm::dot(r, v);
    spec = spec > 0.0f ? spec : 0.0f;
    spec *= spec;
    spec *= spec;
    spec *= spec;
    spec *= spec;
    spec *= spec;
    const glm::vec3 color = 0.15f * albedo + diffuse * albedo + glm::vec3(0.4f * spec);
    return {color, 1.0f};
  }

  // fragment() for 16 pixels at once: the same operations in the same order, so both give identical images.
  template <class L>
  FACET_LANES_INLINE simd::ColorT<L> fragment_lanes(const FragmentLanes<Varyings, L>& f) const {
    using namespace simd;
    FACET_LANE_TYPES(L);
    const Vec3 n = normalize(f.get(&Varyings::world_normal));
    const Vec3 v = normalize(eye - f.get(&Varyings::world_pos));
    const Float n_dot_l = dot(n, light_dir);
    const Vec3 r = (2.0f * n_dot_l) * n - light_dir;
    const Color albedo = texture->sample_lanes(f.get(&Varyings::uv), sampler);
    const Float diffuse = select(n_dot_l > 0.0f, n_dot_l, splat<L>(0.0f));
    Float spec = dot(r, v);
    spec = select(spec > 0.0f, spec, splat<L>(0.0f));
    spec *= spec;
    spec *= spec;
    spec *= spec;
    spec *= spec;
    spec *= spec;
    const Float highlight = 0.4f * spec;
    return {0.15f * albedo.r + diffuse * albedo.r + highlight, 0.15f * albedo.g + diffuse * albedo.g + highlight,
            0.15f * albedo.b + diffuse * albedo.b + highlight, splat<L>(1.0f)};
  }
};

// No prefetch_lanes: issuing the footprint's lines for every lane cost more than it saved on this benchmark
// (measured: sphere:224, WusonOBJ and the quads 3-8% faster without, sphere:707 and 1414 2-3% slower).
static_assert(!PrefetchingLaneShader<BenchShader>);
static_assert(LaneVertexShader<BenchShader>);
static_assert(ShaderTraits<BenchShader>::fragment_lanes_per_level && ShaderTraits<BenchShader>::vertex_lanes_per_level);

}  // namespace facet::bench

// Compiled once, in bench_shader.cpp, for the CLI, the micro-benchmarks and the tests alike.
FACET_EXTERN_SHADER(facet::bench::BenchShader);
