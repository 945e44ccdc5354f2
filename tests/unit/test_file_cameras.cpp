// test_file_cameras.cpp - glTF cameras: read with their node's pose, and rendered through (--camera-index).
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
#include <vector>

#include "facet/error.hpp"
#include "facet/image_io.hpp"
#include "facet/model_io.hpp"
#include "facet/render_job.hpp"
#include "support/base64.hpp"
#include "support/load_problem.hpp"
#include "support/scratch_dir.hpp"

namespace facet {
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

// A 2 x 2 square at z = 0 and cameras on nodes: at z = 5 looking down -z, and turned half round at z = -5.
std::string square_with_cameras(const std::string& cameras) {
  const float positions[] = {-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0};
  const std::uint32_t indices[] = {0, 1, 2, 0, 2, 3};
  std::string buffer(sizeof positions + sizeof indices, '\0');
  std::memcpy(buffer.data(), positions, sizeof positions);
  std::memcpy(buffer.data() + sizeof positions, indices, sizeof indices);
  return R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0,1,2]}],)"
         R"("nodes":[{"mesh":0},{"camera":0,"translation":[0,0,5]},)"
         R"({"camera":1,"translation":[0,0,-5],"rotation":[0,1,0,0]}],)"
         R"("cameras":)" +
         cameras +
         R"(,"meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1}]}],)"
         R"("accessors":[{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3","min":[-1,-1,0],"max":[1,1,0]},)"
         R"({"bufferView":1,"componentType":5125,"count":6,"type":"SCALAR"}],)"
         R"("bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":48},{"buffer":0,"byteOffset":48,"byteLength":24}],)"
         R"("buffers":[{"byteLength":72,"uri":"data:application/octet-stream;base64,)" +
         test::base64(buffer) + R"("}]})";
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
                          R"({"type":"orthographic","orthographic":{"xmag":9,"ymag":2,"znear":0.1,"zfar":20}}])"));
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

}  // namespace
}  // namespace facet
