// test_file_cameras.cpp - glTF scenes seen through their own cameras: the cameras, and materials' sides and alpha.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <glm/glm.hpp>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "facet/error.hpp"
#include "facet/image_io.hpp"
#include "facet/model_io.hpp"
#include "facet/render_job.hpp"
#include "support/gltf_square.hpp"
#include "support/load_problem.hpp"
#include "support/npy.hpp"
#include "support/scratch_dir.hpp"

namespace facet::file_cameras_tests {
namespace {

namespace fs = std::filesystem;

TEST(FileCameras, ReadWithTheirNodesPose) {
  const Mesh mesh = load_model("/usr/share/assimp/models/glTF2/cameras/Cameras.gltf");
  ASSERT_EQ(mesh.cameras.size(), 2u);
  const ModelCamera& perspective = mesh.cameras[0];
  EXPECT_TRUE(perspective.perspective);
  EXPECT_FLOAT_EQ(perspective.yfov_radians, 0.7f);
  EXPECT_FLOAT_EQ(perspective.znear, 0.01f);
  EXPECT_FLOAT_EQ(perspective.zfar.value_or(0.0f), 100.0f);
  EXPECT_EQ(perspective.world_from_camera[3], glm::vec4(0.5f, 0.5f, 3.0f, 1.0f));
  const ModelCamera& orthographic = mesh.cameras[1];
  EXPECT_FALSE(orthographic.perspective);
  EXPECT_EQ(orthographic.magnification, glm::vec2(1.0f));
}

// The square of gltf_square.hpp, and cameras on nodes: at z = 5 looking down -z, and turned half round at z = -5.
// `material`, if given, is the square's material.
std::string square_with_cameras(const std::string& cameras, const std::string& material = "") {
  return test::square_gltf(R"({"camera":0,"translation":[0,0,5]},)"
                           R"({"camera":1,"translation":[0,0,-5],"rotation":[0,1,0,0]})",
                           2, R"(,"cameras":)" + cameras, material);
}

// The rows and columns the mask covers: first and one past the last.
std::array<int, 4> mask_box(const fs::path& mask_png) {
  int w = 0, h = 0;
  const std::vector<std::uint8_t> mask = read_png(mask_png, w, h);
  std::array<int, 4> box{w, h, 0, 0};
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      if (mask[(static_cast<std::size_t>(y) * w + x) * 4] != 0) {
        box = {std::min(box[0], x), std::min(box[1], y), std::max(box[2], x + 1), std::max(box[3], y + 1)};
      }
  return box;
}

// yfov = 2 atan(0.4) from 5 away sees 2 units of height: the square fills the middle half vertically, and as much
// horizontally in a wider image (the image's aspect, not the file's, sets the width). ymag 2 does the same.
TEST(FileCameras, RenderThroughTheFilesCamera) {
  const fs::path dir = test::scratch_dir("file_cameras");
  const std::string yfov = std::to_string(2.0 * std::atan(0.4));
  const fs::path model = test::write_file(
      dir, "square.gltf",
      square_with_cameras(R"([{"type":"perspective","perspective":{"yfov":)" + yfov +
                          R"(,"znear":0.1,"aspectRatio":4.0}},)"
                          R"({"type":"orthographic","orthographic":{"xmag":9,"ymag":2,"znear":0.1,"zfar":20}}])",
                          R"({"doubleSided":true})"));  // camera 1 sees the back
  Renderer renderer(2);
  for (const int index : {0, 1}) {
    RenderJob job;
    job.model = model;
    job.width = 160;
    job.height = 80;
    job.camera.file_camera = index;
    job.outputs = {.color = dir / "c.png", .mask = dir / "m.png"};
    render(job, renderer);
    EXPECT_EQ(mask_box(dir / "m.png"), (std::array<int, 4>{60, 20, 100, 60})) << "camera " << index;
  }
}

TEST(FileCameras, RefusesMissingAndBrokenCameras) {
  const fs::path dir = test::scratch_dir("file_cameras");
  const fs::path model =
      test::write_file(dir, "broken.gltf",
                       square_with_cameras(R"([{"type":"perspective","perspective":{"yfov":0.5,"znear":0.1}},)"
                                           R"({"type":"perspective","perspective":{"yfov":0.5,"znear":0}}])"));
  Renderer renderer(1);
  RenderJob job;
  job.model = model;
  job.width = job.height = 16;
  job.outputs = {.color = dir / "c.png"};
  job.camera.file_camera = 2;
  EXPECT_THROW(render(job, renderer), std::invalid_argument);
  job.camera.file_camera = 1;
  EXPECT_THROW(render(job, renderer), InputError);
  EXPECT_FALSE(fs::exists(dir / "c.png"));
  job.camera.file_camera = 0;
  EXPECT_NO_THROW(render(job, renderer));
  const Mesh without = load_model("/usr/share/assimp/models/OBJ/box.obj");
  EXPECT_THROW(file_camera_view(without, 0, {}, 1.0f, "box.obj"), std::invalid_argument);
}

const std::string kTwoCameras = R"([{"type":"perspective","perspective":{"yfov":0.8,"znear":0.1}},)"
                                R"({"type":"perspective","perspective":{"yfov":0.8,"znear":0.1}}])";

// How many pixels the mask of a render through camera `index` covers, and the colour at the centre.
struct Seen {
  int pixels = 0;
  glm::ivec4 center{0};
};

Seen render_through(const fs::path& model, int index, const LookSpec& look) {
  RenderJob job;
  job.model = model;
  job.width = job.height = 32;
  job.samples = 1;  // pixel counts compared between scenes: pixel centres, not sample 0's offset position
  job.camera.file_camera = index;
  job.look = look;
  const fs::path dir = model.parent_path();
  job.outputs = {.color = dir / "c.png", .mask = dir / "m.png"};
  Renderer renderer(1);
  render(job, renderer);
  int w = 0, h = 0;
  const std::vector<std::uint8_t> mask = read_png(dir / "m.png", w, h), color = read_png(dir / "c.png", w, h);
  Seen seen;
  for (int i = 0; i < w * h; ++i) seen.pixels += mask[4 * static_cast<std::size_t>(i)] != 0;
  const std::size_t center = 4 * static_cast<std::size_t>(h / 2 * w + w / 2);
  seen.center = glm::ivec4(color[center], color[center + 1], color[center + 2], color[center + 3]);
  return seen;
}

// A single-sided material shows only its front unless the look asks for no culling; a double-sided one shows its
// back lit as brightly as its front under a headlight (behind the camera either way).
TEST(GltfMaterials, SidesFollowDoubleSided) {
  const fs::path dir = test::scratch_dir("file_cameras");
  const fs::path single = test::write_file(dir, "single.gltf", square_with_cameras(kTwoCameras, R"({})"));
  LookSpec look;
  look.shading = Shading::blinn_phong;
  EXPECT_GT(render_through(single, 0, look).pixels, 100);
  EXPECT_EQ(render_through(single, 1, look).pixels, 0);
  look.cull = CullMode::none;
  EXPECT_GT(render_through(single, 1, look).pixels, 100);

  const fs::path both = test::write_file(dir, "both.gltf", square_with_cameras(kTwoCameras, R"({"doubleSided":true})"));
  look.cull.reset();
  const Seen front = render_through(both, 0, look), back = render_through(both, 1, look);
  EXPECT_EQ(back.pixels, front.pixels);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(back.center[c], front.center[c], 2) << "channel " << c;
}

// BLEND mixes the surface over the background by its alpha; OPAQUE ignores alpha. Both are surfaces in the mask.
TEST(GltfMaterials, AlphaModes) {
  const fs::path dir = test::scratch_dir("file_cameras");
  const std::string red =
      R"("pbrMetallicRoughness":{"baseColorFactor":[1,0,0,0.25]},"extensions":{"KHR_materials_unlit":{}})";
  LookSpec look;
  look.background = glm::vec3(0.0f, 0.0f, 1.0f);
  look.transparent_background = true;
  const Seen blended = render_through(
      test::write_file(dir, "blend.gltf", square_with_cameras(kTwoCameras, "{" + red + R"(,"alphaMode":"BLEND"})")), 0,
      look);
  EXPECT_GT(blended.pixels, 100);
  EXPECT_EQ(blended.center, glm::ivec4(64, 0, 191, 64));  // 0.25 red over alpha-0 blue: alpha 0.25
  const Seen opaque =
      render_through(test::write_file(dir, "opaque.gltf", square_with_cameras(kTwoCameras, "{" + red + "}")), 0, look);
  EXPECT_EQ(opaque.pixels, blended.pixels);
  EXPECT_EQ(opaque.center, glm::ivec4(255, 0, 0, 255));
}

// The square with per-vertex normals and uvs (u along +x, v along +y), seen through camera 0 of kTwoCameras.
std::string lit_square(glm::vec3 normal, const std::string& material, const std::string& images) {
  const float positions[] = {-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0};
  const float uvs[] = {0, 1, 1, 1, 1, 0, 0, 0};  // glTF's top-left origin
  const std::uint32_t indices[] = {0, 1, 2, 0, 2, 3};
  std::string buffer(sizeof positions + 48 + sizeof uvs + sizeof indices, '\0');
  std::memcpy(buffer.data(), positions, sizeof positions);
  for (int k = 0; k < 4; ++k) std::memcpy(buffer.data() + 48 + 12 * k, &normal, 12);
  std::memcpy(buffer.data() + 96, uvs, sizeof uvs);
  std::memcpy(buffer.data() + 128, indices, sizeof indices);
  return R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0,1]}],)"
         R"("nodes":[{"mesh":0},{"camera":0,"translation":[0,0,5]}],"cameras":)" +
         kTwoCameras + R"(,"materials":[)" + material + "]" + images +
         R"(,"meshes":[{"primitives":[{"attributes":{"POSITION":0,"NORMAL":1,"TEXCOORD_0":2},"indices":3,"material":0}]}],)"
         R"("accessors":[{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3","min":[-1,-1,0],"max":[1,1,0]},)"
         R"({"bufferView":1,"componentType":5126,"count":4,"type":"VEC3"},)"
         R"({"bufferView":2,"componentType":5126,"count":4,"type":"VEC2"},)"
         R"({"bufferView":3,"componentType":5125,"count":6,"type":"SCALAR"}],)"
         R"("bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":48},{"buffer":0,"byteOffset":48,"byteLength":48},)"
         R"({"buffer":0,"byteOffset":96,"byteLength":32},{"buffer":0,"byteOffset":128,"byteLength":24}],)"
         R"("buffers":[{"byteLength":152,"uri":"data:application/octet-stream;base64,)" +
         test::base64(buffer) + R"("}]})";
}

// A normal map tilting the normal to (0.6, 0, 0.8) in tangent space lights a flat square as a square whose vertex
// normals are (0.6, 0, 0.8) is lit, and likewise for (0, 0.6, 0.8): tangent space follows u and v.
TEST(GltfMaterials, NormalMapsTiltTheShadingNormal) {
  const fs::path dir = test::scratch_dir("file_cameras");
  const std::string plain = R"({"pbrMetallicRoughness":{"metallicFactor":0,"roughnessFactor":1}})";
  const std::string mapped =
      R"({"pbrMetallicRoughness":{"metallicFactor":0,"roughnessFactor":1},"normalTexture":{"index":0}})";
  const std::string images = R"(,"images":[{"uri":"normal.png"}],"textures":[{"source":0}])";
  // The physically based look (lit by the studio, which differs less from one side to another) and Blinn-Phong's
  // (a headlight).
  for (const Shading shading : {Shading::automatic, Shading::blinn_phong}) {
    LookSpec look;
    look.shading = shading;
    const glm::ivec4 flat =
        render_through(test::write_file(dir, "flat.gltf", lit_square({0, 0, 1}, plain, "")), 0, look).center;
    // 204 and 230 are 0.6 and 0.804 after 2 t - 1; 128 is 0.004.
    for (const auto& [texel, normal] : {std::pair{glm::u8vec3(204, 128, 230), glm::vec3(0.6f, 0.0f, 0.8f)},
                                        std::pair{glm::u8vec3(128, 204, 230), glm::vec3(0.0f, 0.6f, 0.8f)}}) {
      std::vector<std::uint8_t> image;
      for (int i = 0; i < 4; ++i) image.insert(image.end(), {texel.x, texel.y, texel.z, 255});
      write_png(dir / "normal.png", 2, 2, image);
      const glm::ivec4 with_map =
          render_through(test::write_file(dir, "mapped.gltf", lit_square({0, 0, 1}, mapped, images)), 0, look).center;
      const glm::ivec4 tilted =
          render_through(test::write_file(dir, "tilted.gltf", lit_square(normal, plain, "")), 0, look).center;
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(with_map[c], tilted[c], 3) << "normal " << normal.x << "," << normal.y;
      EXPECT_GT(std::abs(flat.r - tilted.r), shading == Shading::blinn_phong ? 8 : 2);  // the tilt shows
    }
  }
}

// MASK keeps the fragments whose alpha reaches the cutoff, opaque, and nothing else: a texture transparent on its
// left half cuts the square in two, in the image, the mask and the ids alike; a factor below the cutoff hides all.
TEST(GltfMaterials, MaskCutsByAlpha) {
  const fs::path dir = test::scratch_dir("file_cameras");
  write_png(dir / "cut.png", 2, 1, std::vector<std::uint8_t>{255, 255, 255, 0, 255, 255, 255, 255});
  const std::string images = R"(,"images":[{"uri":"cut.png"}],"samplers":[{"magFilter":9728,"minFilter":9728}],)"
                             R"("textures":[{"source":0,"sampler":0}])";
  RenderJob job;
  job.model = test::write_file(
      dir, "cut.gltf",
      lit_square({0, 0, 1}, R"({"pbrMetallicRoughness":{"baseColorTexture":{"index":0}},"alphaMode":"MASK"})", images));
  job.samples = 1;  // pixel counts compared with render_through's
  job.width = job.height = 32;
  job.camera.file_camera = 0;
  job.outputs = {.color = dir / "c.png", .ids = dir / "i.npy", .mask = dir / "m.png"};
  Renderer renderer(2);
  render(job, renderer);
  int w = 0, h = 0;
  const std::vector<std::uint8_t> mask = read_png(dir / "m.png", w, h);
  const test::Npy ids = test::read_npy(dir / "i.npy");
  ASSERT_EQ(ids.words.size(), 2u * static_cast<std::size_t>(w * h));
  int left = 0, right = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const std::size_t p = static_cast<std::size_t>(y * w + x);
      const bool drawn = mask[4 * p] != 0;
      EXPECT_EQ(ids.words[2 * p] != kNoSurface, drawn) << x << "," << y;
      (x < w / 2 ? left : right) += drawn;
    }
  EXPECT_EQ(left, 0);
  EXPECT_GT(right, 60);

  const auto covered = [&](const std::string& cutoff) {
    const std::string material =
        R"({"pbrMetallicRoughness":{"baseColorFactor":[1,1,1,0.4]},"alphaMode":"MASK")" + cutoff + "}";
    return render_through(test::write_file(dir, "faint.gltf", lit_square({0, 0, 1}, material, "")), 0, LookSpec{})
        .pixels;
  };
  EXPECT_EQ(covered(""), 0);  // the default cutoff, 0.5
  EXPECT_EQ(covered(R"(,"alphaCutoff":0.3)"), 2 * right);
}

}  // namespace
}  // namespace facet::file_cameras_tests
