// shader_rate_bench.cpp - each stock shader's fragment rate next to the benchmark shader's, on sphere:224.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <memory>
#include <span>

#include "bench/bench_scenes.hpp"
#include "facet/draw.hpp"
#include "facet/scene.hpp"
#include "facet/texture.hpp"

namespace facet::bench {
namespace {

constexpr int kWidth = 1920, kHeight = 1080, kThreads = 2;

// sphere:224 as `facet bench` draws frame 0 of it: the same vertices, model, view and projection.
const BenchGeometry& geometry() {
  static const BenchGeometry g = make_sphere(224);
  return g;
}

// Pixels the frame covers: with the depth test before shading and a closed convex mesh, each is shaded once.
std::int64_t covered(const Framebuffer& fb) {
  return std::count_if(fb.depth().begin(), fb.depth().end(), [](float z) { return z < 1.0f; });
}

void BM_BenchShader(benchmark::State& state) {
  const Texture texture = make_checker_texture();
  BenchShader shader;
  shader.texture = &texture;
  shader.set_model(model_matrix(0, 1.0f, false));
  shader.clip_from_world = multiply(projection_matrix(kWidth, kHeight), view_matrix());
  Renderer renderer(kThreads);
  Framebuffer fb(kWidth, kHeight);
  const BenchGeometry& g = geometry();
  for (auto _ : state) {
    renderer.clear(fb, glm::vec4(0.1f, 0.1f, 0.15f, 1.0f));
    renderer.draw(fb, shader, std::span<const BenchVertex>(g.vertices), g.indices);
    renderer.finish(fb);
  }
  state.SetItemsProcessed(state.iterations() * covered(fb));
}
BENCHMARK(BM_BenchShader)->Unit(benchmark::kMillisecond)->UseRealTime();

// The scene layer with one stock shading, as `facet render --shading` draws: one white directional light, back
// faces culled, the mesh's own normals and uvs.
void BM_StockShader(benchmark::State& state) {
  const BenchGeometry& g = geometry();
  auto mesh = std::make_shared<Mesh>();
  for (const BenchVertex& v : g.vertices) {
    mesh->positions.push_back(v.pos);
    mesh->normals.push_back(v.normal);
    mesh->uvs.push_back(v.uv);
  }
  mesh->indices = g.indices;
  Scene scene;
  scene.add(Instance{mesh, model_matrix(0, 1.0f, false)});
  View view;
  view.view_from_world = view_matrix();
  view.clip_from_view = projection_matrix(kWidth, kHeight);
  view.near = 0.1f;
  view.far = 100.0f;
  SceneOptions options;
  options.shading = static_cast<Shading>(state.range(0));
  options.cull = CullMode::back;
  Renderer renderer(kThreads);
  Framebuffer fb(kWidth, kHeight);
  for (auto _ : state) {
    renderer.clear(fb, glm::vec4(0.1f, 0.1f, 0.15f, 1.0f));
    scene.render(renderer, fb, view, options);
    renderer.finish(fb);
  }
  state.SetItemsProcessed(state.iterations() * covered(fb));
}
BENCHMARK(BM_StockShader)
    ->ArgName("shading")
    ->DenseRange(static_cast<int>(Shading::automatic), static_cast<int>(Shading::depth))
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
}  // namespace facet::bench

BENCHMARK_MAIN();
