// pipeline_bench.cpp - micro-benchmarks per stage: clipping, setup and binning, block coverage, whole draws, clears.
#include <benchmark/benchmark.h>

#include <cstring>
#include <glm/gtc/matrix_transform.hpp>
#include <vector>

#include "facet/detail/clip.hpp"
#include "facet/renderer.hpp"
#include "setup/setup.hpp"
#include "support/scenes.hpp"
#include "support/test_shaders.hpp"

namespace {

using namespace facet;

constexpr int kWidth = 1920, kHeight = 1080;

test::ClipMesh sphere(int n) {
  const glm::mat4 clip_from_object = glm::perspective(glm::radians(45.0f), float(kWidth) / kHeight, 0.1f, 100.0f) *
                                     glm::translate(glm::mat4(1.0f), glm::vec3(0, 0, -3));
  return test::closed_sphere(n, n, clip_from_object);
}

std::vector<detail::ProjectedVertex> project(const test::ClipMesh& mesh) {
  std::vector<detail::ProjectedVertex> projected;
  for (const glm::vec4& c : mesh.clip) projected.push_back(detail::project_vertex(c, kWidth, kHeight));
  return projected;
}

void BM_ClipCrossingTriangle(benchmark::State& state) {
  const glm::vec4 tri[3] = {{0, 0, 0.3f, 0.5f}, {2.2f, 0, -0.7f, -0.5f}, {0, 0.2f, 0.9f, 1.5f}};
  detail::ClipVertex out[detail::kMaxClipVertices];
  for (auto _ : state) benchmark::DoNotOptimize(detail::clip_triangle(tri, out));
}
BENCHMARK(BM_ClipCrossingTriangle);

// Setup and binning of one chunk of a 1M-triangle sphere at 1080p, single thread.
void BM_SetupChunk(benchmark::State& state) {
  const test::ClipMesh mesh = sphere(707);
  const std::vector<detail::ProjectedVertex> projected = project(mesh);
  const Framebuffer fb(kWidth, kHeight);
  detail::SetupChunk chunk;
  const std::size_t tiles = static_cast<std::size_t>(fb.tiles_x()) * fb.tiles_y();
  for (auto _ : state) {
    chunk.reset();
    const detail::SetupInput input{mesh.clip.data(), projected.data(), mesh.clip.size(), mesh.indices, nullptr, 200000,
                                   detail::kSetupChunk, kWidth, kHeight, fb.tiles_x(), CullMode::back, 1.0f};
    detail::setup_triangles(input, chunk);
    chunk.sort_by_tile(tiles);
    benchmark::DoNotOptimize(chunk.binned.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(detail::kSetupChunk));
}
BENCHMARK(BM_SetupChunk);

void BM_BlockCoverage(benchmark::State& state) {
  const test::ClipMesh mesh = sphere(64);
  const Framebuffer fb(kWidth, kHeight);
  detail::SetupChunk chunk;
  chunk.reset();
  const std::vector<detail::ProjectedVertex> projected = project(mesh);
  detail::setup_triangles({mesh.clip.data(), projected.data(), mesh.clip.size(), mesh.indices, nullptr, 0, mesh.indices.size() / 3,
                           kWidth, kHeight, fb.tiles_x(), CullMode::back, 1.0f},
                          chunk);
  std::size_t blocks = 0;
  for (auto _ : state)
    for (const detail::TriangleSetup& t : chunk.triangles)
      for (int by = t.min_y & ~7; by <= t.max_y; by += 8)
        for (int bx = t.min_x & ~7; bx <= t.max_x; bx += 8, ++blocks)
          benchmark::DoNotOptimize(detail::raster_block_coverage(t, bx, by));
  state.SetItemsProcessed(static_cast<std::int64_t>(blocks));
}
BENCHMARK(BM_BlockCoverage);

// A whole frame: clear, draw a sphere with per-vertex colour, finish. Arguments: sphere N, threads.
void BM_DrawSphere(benchmark::State& state) {
  const test::ClipMesh mesh = sphere(static_cast<int>(state.range(0)));
  std::vector<test::ColorShader::Vertex> vertices;
  for (std::size_t i = 0; i < mesh.clip.size(); ++i) vertices.push_back({mesh.clip[i], mesh.color[i]});
  Renderer renderer(static_cast<int>(state.range(1)));
  Framebuffer fb(kWidth, kHeight);
  for (auto _ : state) {
    renderer.clear(fb, glm::vec4(0.1f, 0.1f, 0.15f, 1.0f));
    renderer.draw(fb, test::ColorShader{}, std::span<const test::ColorShader::Vertex>(vertices), mesh.indices);
    renderer.finish(fb);
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(mesh.indices.size() / 3));
}
BENCHMARK(BM_DrawSphere)->Args({224, 1})->Args({224, 2})->Args({707, 1})->Args({707, 2})->Unit(benchmark::kMillisecond);

void BM_ClearAndFinish(benchmark::State& state) {
  Renderer renderer(static_cast<int>(state.range(0)));
  Framebuffer fb(kWidth, kHeight);
  for (auto _ : state) {
    renderer.clear(fb, glm::vec4(0.1f, 0.1f, 0.15f, 1.0f));
    renderer.finish(fb);
    benchmark::ClobberMemory();
  }
}
BENCHMARK(BM_ClearAndFinish)->Arg(1)->Arg(2)->Unit(benchmark::kMicrosecond);

// The floor for a clear: memset of the same colour and depth buffers.
void BM_MemsetFrame(benchmark::State& state) {
  std::vector<std::uint32_t> color(static_cast<std::size_t>(kWidth) * kHeight);
  std::vector<float> depth(color.size());
  for (auto _ : state) {
    std::memset(color.data(), 0x1a, color.size() * 4);
    std::memset(depth.data(), 0, depth.size() * 4);
    benchmark::ClobberMemory();
  }
}
BENCHMARK(BM_MemsetFrame)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
