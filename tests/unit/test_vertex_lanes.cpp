// test_vertex_lanes.cpp - the vertex stage's 16-lane path gives exactly what vertex() and project_vertex give; lane
// structs are aligned.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <bit>
#include <cstdint>
#include <random>
#include <vector>

#include "bench/bench_shader.hpp"
#include "facet/detail/vertex_stage.hpp"
#include "core/setup/project.hpp"

namespace facet::detail::vertex_lanes_tests {
namespace {

using bench::BenchShader;
using bench::BenchVertex;

std::uint32_t bits(float v) { return std::bit_cast<std::uint32_t>(v); }

BenchShader make_shader() {
  BenchShader shader;
  shader.set_model(glm::rotate(glm::scale(glm::mat4(1), glm::vec3(1.3f)), 0.9f, glm::vec3(0.2f, 1.0f, -0.4f)));
  shader.clip_from_world = glm::perspective(glm::radians(50.0f), 1.6f, 0.1f, 20.0f) *
                           glm::lookAt(glm::vec3(0.3f, 0.4f, 3.0f), glm::vec3(0.0f), glm::vec3(0, 1, 0));
  return shader;
}

// Vertices inside, across and behind the frustum, with unnormalised normals.
std::vector<BenchVertex> random_vertices(std::size_t count) {
  std::mt19937 rng(77);
  std::uniform_real_distribution<float> any(-4.0f, 4.0f);
  std::vector<BenchVertex> vertices(count);
  for (BenchVertex& v : vertices)
    v = {{any(rng), any(rng), any(rng)}, {any(rng), any(rng), any(rng)}, {any(rng), any(rng)}};
  return vertices;
}

// Shades vertices [begin, end) with the vertex stage (the lane path for whole groups of 16, vertex() for the
// rest) and checks each against vertex() and project_vertex.
void check_range(const BenchShader& shader, const std::vector<BenchVertex>& vertices, std::size_t begin,
                 std::size_t end) {
  constexpr std::size_t kFloats = float_count_v<BenchShader::Varyings>;
  const std::size_t n = end - begin;
  std::vector<glm::vec4> clip(n);
  std::vector<ProjectedVertex> projected(n);
  std::vector<float> varyings(n * kFloats);
  const VertexSource<BenchShader> source{&shader, vertices.data()};
  const VertexOutputs out{begin, clip.data(), projected.data(), varyings.data(), 640, 480};
  VertexSource<BenchShader>::shade(&source, begin, end, out);
  for (std::size_t i = begin; i < end; ++i) {
    const VertexOut<BenchShader::Varyings> expected = shader.vertex(vertices[i]);
    const FloatArray<BenchShader::Varyings> floats = to_floats(expected.varyings);
    const std::size_t slot = i - begin;
    for (int c = 0; c < 4; ++c)
      ASSERT_EQ(bits(clip[slot][c]), bits(expected.clip[c])) << "vertex " << i << " clip " << c;
    for (std::size_t f = 0; f < kFloats; ++f)
      ASSERT_EQ(bits(varyings[slot * kFloats + f]), bits(floats[f])) << "vertex " << i << " varying " << f;
    const ProjectedVertex p = project_vertex(expected.clip, 640, 480);
    ASSERT_EQ(projected[slot].outcode, p.outcode) << "vertex " << i;
    ASSERT_EQ(projected[slot].x, p.x) << "vertex " << i;
    ASSERT_EQ(projected[slot].y, p.y) << "vertex " << i;
    ASSERT_EQ(bits(projected[slot].z), bits(p.z)) << "vertex " << i;
  }
}

TEST(VertexLanes, BenchShaderLanesMatchItsVertexFunction) {
  const BenchShader shader = make_shader();
  const std::vector<BenchVertex> vertices = random_vertices(1000);
  check_range(shader, vertices, 0, vertices.size());
}

// Ranges that start anywhere and hold no, part of, or several groups of 16 and projection blocks of 64.
TEST(VertexLanes, AnyRangeMixesLaneGroupsAndSingleVertices) {
  const BenchShader shader = make_shader();
  const std::vector<BenchVertex> vertices = random_vertices(300);
  for (const std::size_t begin : {std::size_t{0}, std::size_t{5}, std::size_t{17}})
    for (const std::size_t n : {std::size_t{1}, std::size_t{15}, std::size_t{16}, std::size_t{33}, std::size_t{64},
                                std::size_t{65}, std::size_t{200}})
      check_range(shader, vertices, begin, begin + n);
}

}  // namespace
}  // namespace facet::detail::vertex_lanes_tests

namespace facet::vertex_lanes_tests {
namespace {

// Lane structs made in baseline code (this test is compiled without AVX-512) are read by the AVX-512 clones with
// aligned 64-byte loads, so they must be 64-byte aligned wherever they are allocated.
TEST(LaneTypes, StructsOfLanesAre64ByteAlignedInAnyCode) {
  using Varyings = bench::BenchShader::Varyings;
  static_assert(alignof(FragmentLanes<Varyings>) == 64 && alignof(VertexOutLanes<Varyings>) == 64);
  static_assert(alignof(simd::Vec2) == 64 && alignof(simd::Vec3) == 64 && alignof(simd::Color) == 64);
  for (const std::size_t n : {std::size_t{1}, std::size_t{3}, std::size_t{100}, std::size_t{4096}}) {
    const std::vector<FragmentLanes<Varyings>> strips(n);
    EXPECT_EQ(reinterpret_cast<std::uintptr_t>(strips.data()) % 64, 0u) << n;
  }
}

}  // namespace
}  // namespace facet::vertex_lanes_tests
