// test_goldens.cpp - the golden images drawn through the job layer and compared byte for byte, in any build.
// tests/golden/golden_images.sh checks them through the CLI; this checks the same pictures without it, so that a
// build without the CLI's libraries (the aarch64 cross build run under QEMU, scripts/test-aarch64.sh) shows that it
// draws exactly what the x86-64 build draws.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <string>
#include <vector>

#include "facet/cpu_level.hpp"
#include "facet/demo_scenes.hpp"
#include "facet/names.hpp"
#include "facet/render_job.hpp"
#include "facet/shaders/stock.hpp"
#include "job/job_frame.hpp"
#include "scene/texture/image_decode.hpp"
#include "support/scratch_dir.hpp"

#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STB_IMAGE_WRITE_STATIC
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wall"
#pragma GCC diagnostic ignored "-Wextra"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wunused-function"
#include <stb/stb_image_write.h>
#pragma GCC diagnostic pop

namespace facet {
namespace {

const std::filesystem::path kModels = "/usr/share/assimp/models";

// A golden of tests/golden/images and the job that draws it, as golden_images.sh asks the CLI for it.
struct Golden {
  std::string name;
  std::function<void(RenderJob&)> set;
};

std::vector<Golden> goldens() {
  const auto demo = [](Demo d, int samples = 1) {
    return [d, samples](RenderJob& job) { job.demo = d, job.samples = samples; };
  };
  const auto model = [](std::filesystem::path path, std::function<void(RenderJob&)> more = {}) {
    return [path, more](RenderJob& job) {
      job.model = kModels / path;
      if (more) more(job);
    };
  };
  const std::filesystem::path wuson = "OBJ/WusonOBJ.obj", box = "OBJ/box.obj";
  const std::filesystem::path gltf = "glTF2";
  std::vector<Golden> out = {
      {"demo_cube", demo(Demo::cube)},
      {"demo_torus", demo(Demo::torus)},
      {"demo_two_cubes", demo(Demo::two_cubes)},
      {"demo_pentagon", demo(Demo::pentagon)},
      {"wireframe", model(wuson, [](RenderJob& job) { job.look.wireframe = true; })},
      {"edges", model(box, [](RenderJob& job) { job.look.edges = true; })},
      {"antialiased_wuson", model(wuson, [](RenderJob& job) { job.samples = 4; })},
      {"antialiased_edges", model(box, [](RenderJob& job) { job.look.edges = true, job.samples = 4; })},
      {"antialiased_demo_torus", demo(Demo::torus, 4)},
      {"gltf_box_textured_binary", model(gltf / "BoxTextured-glTF-Binary/BoxTextured.glb")},
      {"gltf_box_textured_embedded", model(gltf / "BoxTextured-glTF-Embedded/BoxTextured.gltf")},
      {"gltf_box_textured_separate", model(gltf / "BoxTextured-glTF/BoxTextured.gltf")},
      {"gltf_texture_transform", model(gltf / "textureTransform/TextureTransformTest.gltf",
                                       [](RenderJob& job) { job.width = 320, job.height = 240; })},
      {"ply_vertex_colors", model("PLY/float-color.ply")},
      {"stl_binary", model("STL/Spider_binary.stl")},
  };
#ifndef FACET_NO_IMAGE_CODECS
  // Its textures are JPEG files, which a build without libjpeg-turbo decodes with stb_image, whose inverse DCT
  // rounds differently: the golden holds libjpeg-turbo's texels.
  out.push_back({"textured_obj", model("OBJ/spider.obj")});
#endif
  for (const char* p : {"perspective", "orthographic", "frustum", "oblique", "isometric", "dimetric", "trimetric",
                        "front", "top", "side"})
    out.push_back({std::string("projection_") + p,
                   model(wuson, [p](RenderJob& job) { job.camera.projection = *parse_projection(p); })});
  return out;
}

std::vector<unsigned char> file_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Draws every golden at the active CPU level and compares it with tests/golden/images, byte for byte; a golden
// that differs is written beside a diff image, named for the level. Returns how many were compared.
int compare_goldens(const std::string& level) {
  const char* source = std::getenv("FACET_SOURCE_DIR");
  EXPECT_TRUE(source && *source) << "FACET_SOURCE_DIR must name the source tree (ctest sets it)";
  if (!source || !*source) return 0;
  const std::filesystem::path images = std::filesystem::path(source) / "tests/golden/images";
  const std::filesystem::path out = test::scratch_dir("goldens");
  Renderer renderer(2);
  int compared = 0;
  for (const Golden& golden : goldens()) {
    SCOPED_TRACE(golden.name + " at CPU level " + level);
    RenderJob job;
    job.width = 240, job.height = 180, job.samples = 1;
    golden.set(job);
    detail::JobFrame frame =
        job.demo ? detail::demo_job_frame(job, detail::prepare_demo(job), 0) : detail::prepare_job(job);
    Framebuffer target(job.width, job.height, job.samples);
    renderer.clear(target, frame.clear, 1.0f);
    frame.scene.render(renderer, target, frame.view, frame.options);
    renderer.finish(target);
    const std::vector<std::uint8_t> actual = target.rgba8();

    const std::filesystem::path path = images / (golden.name + ".png");
    const std::vector<unsigned char> bytes = file_bytes(path);
    EXPECT_FALSE(bytes.empty()) << path;
    if (bytes.empty()) continue;
    const DecodedImage expected = decode_image(bytes, 16384, path.string());
    EXPECT_EQ(expected.width, job.width);
    EXPECT_EQ(expected.height, job.height);
    if (expected.width != job.width || expected.height != job.height) continue;
    // The goldens are opaque RGB: every colour channel must match.
    std::vector<std::uint8_t> diff(actual.size(), 0);
    int differing = 0;
    for (std::size_t p = 0; p < actual.size(); p += 4) {
      bool same = true;
      for (std::size_t c = 0; c < 3; ++c) same &= actual[p + c] == expected.rgba[p + c];
      differing += same ? 0 : 1;
      diff[p] = same ? 0 : 255;
      diff[p + 3] = 255;
    }
    if (differing > 0) {
      const std::string stem = golden.name + "." + level;
      const std::string actual_png = (out / (stem + ".actual.png")).string();
      const std::string diff_png = (out / (stem + ".diff.png")).string();
      stbi_write_png(actual_png.c_str(), job.width, job.height, 4, actual.data(), job.width * 4);
      stbi_write_png(diff_png.c_str(), job.width, job.height, 4, diff.data(), job.width * 4);
      ADD_FAILURE() << differing << " pixels differ from " << path << " (actual " << actual_png << ", diff " << diff_png
                    << ")";
    }
    ++compared;
  }
  return compared;
}

TEST(Goldens, TheJobLayerDrawsEveryGoldenExactly) { EXPECT_GE(compare_goldens(cpu_level()), 25); }

// Every stock lane shader is a template on the lane layout, so each CPU level's copy runs it in its own registers
// (and the test below compares what the layouts draw).
template <class... S>
constexpr bool per_level_lanes = (ShaderTraits<S>::fragment_lanes_per_level && ...);
static_assert(per_level_lanes<UnlitShader, FlatShader, GouraudShader, SurfaceShader, UntexturedSurfaceShader,
                              NormalShader, DepthShader, EnvironmentBackgroundShader, PbrShader, UntexturedPbrShader,
                              TangentPbrShader>);

// Every CPU level this machine and build can run draws the same bytes: the goldens again at each level below the
// active one (the best there is, unless FACET_CPU caps it).
TEST(Goldens, EveryCpuLevelDrawsTheSameBytes) {
  const std::string active = cpu_level();
  const std::vector<std::string> levels = cpu_levels();
  ASSERT_FALSE(levels.empty());
  for (const std::string& level : levels) {
    if (level == active) break;  // TheJobLayerDrawsEveryGoldenExactly, and the levels above are capped
    set_cpu_level(level);
    EXPECT_EQ(cpu_level(), level);
    EXPECT_GE(compare_goldens(level), 25);
  }
  set_cpu_level(active);
}

}  // namespace
}  // namespace facet
