// pipeline_bench.cpp - micro-benchmarks per stage: vertex work, clipping, setup and binning, coverage, shading, clears.
#include <benchmark/benchmark.h>

#include <cstring>
#include <glm/gtc/matrix_transform.hpp>
#include <vector>

#include "bench/bench_shader.hpp"
#include "core/clip/clip.hpp"
#include "facet/detail/dispatch.hpp"
#include "facet/draw.hpp"
#include "facet/renderer.hpp"
#include "core/setup/project.hpp"
#include "core/setup/setup.hpp"
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

// The vertex stage as the pipeline runs it (VertexSource::shade, in the CPU's dispatch clone): the benchmark
// shader's vertex(), then outcode, w-divide, viewport and snap, and the varyings stored as floats.
void BM_VertexStage(benchmark::State& state) {
  const test::ClipMesh mesh = sphere(707);
  std::vector<bench::BenchVertex> vertices;
  for (const glm::vec4& c : mesh.clip) vertices.push_back({glm::vec3(c), glm::vec3(c), glm::vec2(c)});
  bench::BenchShader shader;
  shader.clip_from_world = glm::perspective(glm::radians(45.0f), float(kWidth) / kHeight, 0.1f, 100.0f) *
                           glm::translate(glm::mat4(1.0f), glm::vec3(0, 0, -3));
  std::vector<float> varyings(vertices.size() * float_count_v<bench::BenchShader::Varyings>);
  std::vector<detail::ProjectedVertex> projected(vertices.size());
  const detail::VertexSource<bench::BenchShader> source{&shader, vertices.data()};
  const detail::VertexOutputs out{0, nullptr, projected.data(), varyings.data(), kWidth, kHeight};
  for (auto _ : state) {
    detail::VertexSource<bench::BenchShader>::shade(&source, 0, vertices.size(), out);
    benchmark::DoNotOptimize(projected.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(vertices.size()));
}
BENCHMARK(BM_VertexStage)->Unit(benchmark::kMillisecond);

// Fragment shading alone: the benchmark shader (Lambert + Phong, bilinear 1024^2 texture) on strips of 16 pixels,
// through fragment_lanes (as the pipeline runs it, in the CPU's dispatch clone) or 16 scalar fragment() calls.
struct ShadeFixture {
  Texture texture;
  bench::BenchShader shader;
  std::vector<FragmentLanes<bench::BenchShader::Varyings>> strips;
  ShadeFixture() {
    std::vector<std::uint32_t> texels(1024 * 1024);
    for (std::size_t i = 0; i < texels.size(); ++i) texels[i] = static_cast<std::uint32_t>(i * 2654435761u);
    texture = Texture(1024, 1024, std::move(texels));
    shader.texture = &texture;
    strips.resize(4096);
    for (std::size_t s = 0; s < strips.size(); ++s)
      for (int k = 0; k < simd::kLanes; ++k) {
        const float t = static_cast<float>(s * simd::kLanes + static_cast<std::size_t>(k)) * 1e-4f;
        const float v[8] = {std::sin(t), std::cos(t), 0.5f, std::sin(t), std::cos(t), 0.5f, t, 0.5f * t};
        for (int f = 0; f < 8; ++f) strips[s].varyings[static_cast<std::size_t>(f)][k] = v[f];
      }
  }
};

std::uint32_t shade_strips_lanes(const ShadeFixture& fx) {
  return facet::detail::at_cpu_level([&]() __attribute__((always_inline)) {
    simd::UInt sum{};
    for (const auto& strip : fx.strips) sum += simd::pack_rgba8(fx.shader.fragment_lanes(strip));
    return sum[0] ^ sum[15];
  });
}

void BM_ShadeStripLanes(benchmark::State& state) {
  const ShadeFixture fx;
  for (auto _ : state) benchmark::DoNotOptimize(shade_strips_lanes(fx));
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(fx.strips.size() * simd::kLanes));
}
BENCHMARK(BM_ShadeStripLanes)->Unit(benchmark::kMicrosecond);

void BM_ShadeFragmentsScalar(benchmark::State& state) {
  const ShadeFixture fx;
  for (auto _ : state) {
    std::uint32_t sum = 0;
    for (const auto& strip : fx.strips)
      for (int k = 0; k < simd::kLanes; ++k) {
        Fragment<bench::BenchShader::Varyings> f;
        FloatArray<bench::BenchShader::Varyings> values;
        for (std::size_t i = 0; i < values.size(); ++i) values[i] = strip.varyings[i][k];
        f.varyings = from_floats<bench::BenchShader::Varyings>(values);
        sum += pack_rgba8(fx.shader.fragment(f));
      }
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(fx.strips.size() * simd::kLanes));
}
BENCHMARK(BM_ShadeFragmentsScalar)->Unit(benchmark::kMicrosecond);

void BM_ClipCrossingTriangle(benchmark::State& state) {
  const glm::vec4 tri[3] = {{0, 0, 0.3f, 0.5f}, {2.2f, 0, -0.7f, -0.5f}, {0, 0.2f, 0.9f, 1.5f}};
  detail::ClipVertex out[detail::kMaxClipVertices];
  for (auto _ : state) benchmark::DoNotOptimize(detail::clip_triangle(tri, out));
}
BENCHMARK(BM_ClipCrossingTriangle);

// Setup and binning of one chunk of a 1M-triangle sphere at 1080p, single thread.
// Setup's input for primitives [first, first + count) of a projected mesh: triangles, back faces culled.
detail::SetupInput setup_input(const test::ClipMesh& mesh, const std::vector<detail::ProjectedVertex>& projected,
                               std::size_t first, std::size_t count, const Framebuffer& fb) {
  return {.clip = mesh.clip.data(),
          .projected = projected.data(),
          .vertex_first = 0,
          .clip_position = nullptr,
          .clip_source = nullptr,
          .vertex_count = mesh.clip.size(),
          .indices = mesh.indices,
          .order = nullptr,
          .first = first,
          .count = count,
          .width = kWidth,
          .height = kHeight,
          .tiles_x = fb.tiles_x(),
          .cull = CullMode::back,
          .line_width = 1.0f};
}

void BM_SetupChunk(benchmark::State& state) {
  const test::ClipMesh mesh = sphere(707);
  const std::vector<detail::ProjectedVertex> projected = project(mesh);
  const Framebuffer fb(kWidth, kHeight);
  detail::SetupChunk chunk;
  const std::size_t tiles = static_cast<std::size_t>(fb.tiles_x()) * fb.tiles_y();
  for (auto _ : state) {
    chunk.reset();
    const detail::SetupInput input = setup_input(mesh, projected, 200000, detail::kSetupChunk, fb);
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
  detail::setup_triangles(setup_input(mesh, projected, 0, mesh.indices.size() / 3, fb), chunk);
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

// Each frame clears to another colour than the last: a repeated identical clear of untouched tiles writes nothing.
void BM_ClearAndFinish(benchmark::State& state) {
  Renderer renderer(static_cast<int>(state.range(0)));
  Framebuffer fb(kWidth, kHeight);
  bool odd = false;
  for (auto _ : state) {
    renderer.clear(fb, odd ? glm::vec4(0.1f, 0.1f, 0.15f, 1.0f) : glm::vec4(0.2f, 0.1f, 0.15f, 1.0f));
    renderer.finish(fb);
    odd = !odd;
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
