// test_deferred_bench_shader.cpp - the benchmark shader's lane, prefetching and scalar paths draw the same image.
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "bench/bench_shader.hpp"
#include "facet/draw.hpp"
#include "facet/fragment_lanes.hpp"
#include "facet/texture.hpp"
#include "support/image_asserts.hpp"

namespace facet::test {
namespace {

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"

// The benchmark shader without its lane function: the scalar definition of the same picture.
struct ScalarBenchShader {
  using Vertex = bench::BenchShader::Vertex;
  using Varyings = bench::BenchShader::Varyings;
  static constexpr bool may_discard = false;
  bench::BenchShader inner;
  VertexOut<Varyings> vertex(const Vertex& v) const { return inner.vertex(v); }
  glm::vec4 fragment(const Fragment<Varyings>& f) const { return inner.fragment(f); }
};

// The benchmark shader with prefetch_lanes: strips are prepared kPrefetchDistance strips before they are shaded.
struct PrefetchingBenchShader : bench::BenchShader {
  template <class L>
  FACET_LANES_INLINE void prefetch_lanes(const FragmentLanes<Varyings, L>& f) const {
    texture->prefetch_lanes(f.get(&Varyings::uv), sampler);
  }
};
static_assert(PrefetchingLaneShader<PrefetchingBenchShader>);

// The benchmark shader opts out of per-lane primitive and front_facing: its lanes match without them, below.
static_assert(!ShaderTraits<bench::BenchShader>::lanes_read_primitive);

TEST(DeferredShading, BenchShaderLanesMatchItsScalarFragment) {
  std::vector<bench::BenchVertex> vertices;
  std::vector<std::uint32_t> indices;
  const int n = 48;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) {
      const float theta = 3.14159265f * i / n, phi = 6.2831853f * j / n;
      const glm::vec3 p(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
      vertices.push_back({p, p, {2.0f * j / n, 1.0f - static_cast<float>(i) / n}});  // u wraps once: repeat
    }
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const auto at = [&](int a, int b) { return static_cast<std::uint32_t>(a * (n + 1) + b); };
      indices.insert(indices.end(),
                     {at(i, j), at(i, j + 1), at(i + 1, j), at(i, j + 1), at(i + 1, j + 1), at(i + 1, j)});
    }
  std::mt19937 rng(5);
  std::vector<std::uint32_t> texels(64 * 64);
  for (std::uint32_t& t : texels) t = static_cast<std::uint32_t>(rng());
  const Texture texture(64, 64, std::move(texels));

  bench::BenchShader lanes;
  lanes.texture = &texture;
  lanes.set_model(glm::rotate(glm::mat4(1), 0.7f, glm::vec3(0.3f, 1.0f, 0.1f)));
  lanes.clip_from_world = glm::perspective(glm::radians(45.0f), 1.5f, 0.1f, 10.0f) *
                          glm::lookAt(lanes.eye, glm::vec3(0.0f), glm::vec3(0, 1, 0));
  const ScalarBenchShader scalar{lanes};
  const PrefetchingBenchShader prefetching{lanes};
  const auto draw = [&](const auto& shader, bool deferred, int samples) {
    Framebuffer fb(241, 160, samples);
    Renderer renderer(2);
    renderer.clear(fb);
    RenderState state;
    state.defer_shading = deferred;
    renderer.draw(fb, shader, std::span<const bench::BenchVertex>(vertices), indices, state);
    renderer.finish(fb);
    return fb;
  };
  // With 4 samples, the deferred passes shade a triangle new to a pixel's later sample with masked lanes.
  for (const int samples : {1, 4}) {
    const Framebuffer expected = draw(scalar, false, samples);
    const auto drawn =
        std::count_if(expected.depth().begin(), expected.depth().end(), [](float z) { return z < 1.0f; });
    ASSERT_GT(drawn, 241 * 160 / 4);  // the sphere fills a good part of the frame
    const std::string n = std::to_string(samples) + " samples: ";
    expect_same(expected, draw(scalar, true, samples), (n + "deferred, scalar fragment").c_str());
    expect_same(expected, draw(lanes, true, samples), (n + "deferred, lane fragment").c_str());
    expect_same(expected, draw(prefetching, true, samples), (n + "deferred, lane fragment prepared ahead").c_str());
    expect_same(expected, draw(lanes, false, samples), (n + "immediate, lane shader's scalar fragment").c_str());
  }
}

#pragma GCC diagnostic pop

}  // namespace
}  // namespace facet::test
