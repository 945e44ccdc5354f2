// image_bench.cpp - PNG encoding of a rendered 1920x1080 frame: facet's writer against stb_image_write.
#include <benchmark/benchmark.h>

#include <cstdint>
#include <memory>
#include <vector>

#include "facet/framebuffer.hpp"
#include "facet/model_io.hpp"
#include "facet/render_job.hpp"
#include "job/io/png.hpp"

// The one stb_image_write implementation in facet's tree: only this comparison uses it.
#define STB_IMAGE_WRITE_IMPLEMENTATION
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wsign-compare"
#include <stb_image_write.h>
#pragma GCC diagnostic pop

namespace {

// WusonOBJ as `facet render` draws it at 1920x1080: RGBA bytes, top row first.
const std::vector<std::uint8_t>& frame() {
  static const std::vector<std::uint8_t> rgba = [] {
    const auto mesh = std::make_shared<facet::Mesh>(facet::load_model("/usr/share/assimp/models/OBJ/WusonOBJ.obj"));
    const facet::View view =
        facet::make_view(facet::CameraSpec{}, facet::framing_of(*mesh, "wuson"), 1920.0f / 1080.0f);
    const facet::LookSpec look;
    facet::Scene scene;
    scene.add(facet::Instance{mesh, glm::mat4(1.0f)});
    facet::Renderer renderer(1);
    facet::Framebuffer target(1920, 1080);
    renderer.clear(target, facet::clear_color(look, facet::kDefaultBackground), 1.0f);
    scene.render(renderer, target, view,
                 facet::scene_options(look, view.view_from_world, facet::Shading::automatic,
                                      facet::kDefaultBackground));
    renderer.finish(target);
    return target.rgba8();
  }();
  return rgba;
}

void append(void* context, void* data, int size) {
  auto* out = static_cast<std::vector<std::uint8_t>*>(context);
  out->insert(out->end(), static_cast<std::uint8_t*>(data), static_cast<std::uint8_t*>(data) + size);
}

// range(0) threads; range(1) channels written: 4 (RGBA), or 3 (RGB, what `facet render` writes over an opaque
// background), from the framebuffer's RGBA.
void BM_FacetPng(benchmark::State& state) {
  const std::vector<std::uint8_t>& rgba = frame();
  std::size_t bytes = 0;
  const auto threads = static_cast<int>(state.range(0)), channels = static_cast<int>(state.range(1));
  for (auto _ : state) {
    const std::vector<std::uint8_t> png = facet::encode_png(1920, 1080, channels, rgba, 4, threads);
    bytes = png.size();
    benchmark::DoNotOptimize(png.data());
  }
  state.counters["file_bytes"] = static_cast<double>(bytes);
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * rgba.size()));
}
BENCHMARK(BM_FacetPng)
    ->ArgsProduct({{1, 2}, {4, 3}})
    ->ArgNames({"threads", "channels"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

void BM_StbPng(benchmark::State& state) {
  const std::vector<std::uint8_t>& rgba = frame();
  std::size_t bytes = 0;
  for (auto _ : state) {
    std::vector<std::uint8_t> png;
    stbi_write_png_to_func(&append, &png, 1920, 1080, 4, rgba.data(), 1920 * 4);
    bytes = png.size();
    benchmark::DoNotOptimize(png.data());
  }
  state.counters["file_bytes"] = static_cast<double>(bytes);
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * rgba.size()));
}
BENCHMARK(BM_StbPng)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
