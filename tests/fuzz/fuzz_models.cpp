// fuzz_models.cpp - libFuzzer targets for the model readers (OBJ with MTL, PLY, STL, glTF and GLB, XYZ, PCD, .splat),
// one per format, chosen at compile time by FACET_FUZZ_FORMAT.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

#include "fuzz_input.hpp"
#include "facet/framebuffer.hpp"
#include "facet/renderer.hpp"
#include "facet/splats.hpp"
#include "facet/view_spec.hpp"
#include "job/io/loaders.hpp"
#include "job/io/splat_loader.hpp"

namespace {

// An empty folder for the model: the files an input names (MTL libraries, buffers, images) are looked for there
// and not found, except those the seed corpus put beside it.
[[maybe_unused]] const std::filesystem::path& model_path() {
  static const std::filesystem::path path = [] {
    const std::filesystem::path folder = std::filesystem::temp_directory_path() / "facet-fuzz-model";
    std::filesystem::create_directories(folder);
    return folder / "input";
  }();
  return path;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  facet::FileBytes bytes(reinterpret_cast<const char*>(data), size);
  [[maybe_unused]] const facet::LoadOptions options;
  return facet::fuzz::run([&] {
    const std::string source = "input";
#if FACET_FUZZ_FORMAT == 1
    (void)facet::load_obj(model_path(), bytes, source, options);
#elif FACET_FUZZ_FORMAT == 2
    // Two threads from the first byte: the two-half reader, and the one-thread reader it falls back to.
    (void)facet::load_ply(bytes, source, 2, 0);
#elif FACET_FUZZ_FORMAT == 3
    (void)facet::load_stl(bytes, source);
#elif FACET_FUZZ_FORMAT == 4
    // The model is posed too: at rest (skins and morph weights), and each of its first animations half way through
    // and past its end, so hostile keys, joints and weights reach the sampler and the skinning.
    const facet::Model model = facet::load_gltf(model_path(), bytes, source, options);
    (void)facet::pose(model, std::nullopt, 0.0, source);
    for (std::size_t a = 0; a < model.animations.size() && a < 3; ++a)
      for (const double t : {0.5 * model.animations[a].duration(), 1e6})
        (void)facet::pose(model, a, t, source);
#elif FACET_FUZZ_FORMAT == 5
    (void)facet::load_xyz(bytes, source);
#elif FACET_FUZZ_FORMAT == 6
    (void)facet::load_pcd(bytes, source);
#elif FACET_FUZZ_FORMAT == 7
    // The Gaussians are drawn too, into a small frame that sees them all: hostile scales, rotations and opacities
    // reach the rasterizer.
    const facet::Mesh mesh = facet::load_splat(bytes, source);
    const facet::Framing framing = facet::framing_of(mesh, source);
    const facet::View view = facet::make_view(facet::CameraSpec{}, framing, 4.0f / 3.0f);
    static facet::Renderer renderer(1);
    facet::Framebuffer target(64, 48);
    renderer.clear(target, glm::vec4(0.0f), 1.0f);
    renderer.finish(target);
    facet::render_splats(renderer, target, view, *mesh.splats);
#else
#error "FACET_FUZZ_FORMAT: 1 OBJ, 2 PLY, 3 STL, 4 glTF, 5 XYZ, 6 PCD, 7 .splat"
#endif
  });
}
