// test_format_parity.cpp - one mesh written as OBJ, glTF (a data: URI buffer), PLY and STL draws one image.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "facet/image_io.hpp"
#include "facet/model_io.hpp"
#include "facet/render_job.hpp"
#include "support/base64.hpp"
#include "support/load_problem.hpp"
#include "support/scratch_dir.hpp"

namespace facet::format_parity_tests {
namespace {

namespace fs = std::filesystem;

// A square pyramid with its vertices numbered in order of first use, so STL's welding numbers them alike.
const std::vector<glm::vec3> kPositions = {{0, 1, 0}, {-1, 0, 1}, {1, 0, 1}, {1, 0, -1}, {-1, 0, -1}};
const std::vector<std::uint32_t> kIndices = {0, 1, 2, 0, 2, 3, 0, 3, 4, 0, 4, 1, 1, 4, 3, 1, 3, 2};

std::string obj() {
  std::string text;
  for (const glm::vec3& p : kPositions)
    text += "v " + std::to_string(p.x) + " " + std::to_string(p.y) + " " + std::to_string(p.z) + "\n";
  for (std::size_t t = 0; t < kIndices.size(); t += 3)
    text += "f " + std::to_string(kIndices[t] + 1) + " " + std::to_string(kIndices[t + 1] + 1) + " " +
            std::to_string(kIndices[t + 2] + 1) + "\n";
  return text;
}

std::string ply() {
  std::string text =
      "ply\nformat ascii 1.0\nelement vertex 5\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 6\nproperty list uchar int vertex_indices\nend_header\n";
  for (const glm::vec3& p : kPositions)
    text += std::to_string(p.x) + " " + std::to_string(p.y) + " " + std::to_string(p.z) + "\n";
  for (std::size_t t = 0; t < kIndices.size(); t += 3)
    text += "3 " + std::to_string(kIndices[t]) + " " + std::to_string(kIndices[t + 1]) + " " +
            std::to_string(kIndices[t + 2]) + "\n";
  return text;
}

std::string stl() {
  std::string text = "solid pyramid\n";
  for (std::size_t t = 0; t < kIndices.size(); t += 3) {
    text += "facet normal 0 0 0\nouter loop\n";
    for (std::size_t k = 0; k < 3; ++k) {
      const glm::vec3& p = kPositions[kIndices[t + k]];
      text += "vertex " + std::to_string(p.x) + " " + std::to_string(p.y) + " " + std::to_string(p.z) + "\n";
    }
    text += "endloop\nendfacet\n";
  }
  return text + "endsolid pyramid\n";
}

std::string gltf() {
  std::string buffer(kPositions.size() * 12 + kIndices.size() * 4, '\0');
  std::memcpy(buffer.data(), kPositions.data(), kPositions.size() * 12);
  std::memcpy(buffer.data() + kPositions.size() * 12, kIndices.data(), kIndices.size() * 4);
  const std::string positions = std::to_string(kPositions.size() * 12), indices = std::to_string(kIndices.size() * 4);
  return R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],)"
         // The look the other formats' material-less meshes get (glTF's own default is a rough metal).
         R"("materials":[{"pbrMetallicRoughness":{"metallicFactor":0,"roughnessFactor":0.5},"doubleSided":true}],)"
         R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1,"material":0}]}],)"
         R"("accessors":[{"bufferView":0,"componentType":5126,"count":5,"type":"VEC3","min":[-1,0,-1],"max":[1,1,1]},)"
         R"({"bufferView":1,"componentType":5125,"count":18,"type":"SCALAR"}],)"
         R"("bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":)" +
         positions + R"(},{"buffer":0,"byteOffset":)" + positions + R"(,"byteLength":)" + indices +
         R"(}],)"
         R"("buffers":[{"byteLength":)" +
         std::to_string(buffer.size()) + R"(,"uri":"data:application/octet-stream;base64,)" + test::base64(buffer) +
         R"("}]})";
}

TEST(FormatParity, OneMeshInEveryFormatDrawsTheSameImage) {
  const fs::path dir = test::scratch_dir("parity");
  const fs::path files[] = {test::write_file(dir, "pyramid.obj", obj()), test::write_file(dir, "pyramid.gltf", gltf()),
                            test::write_file(dir, "pyramid.ply", ply()), test::write_file(dir, "pyramid.stl", stl())};
  Renderer renderer(2);
  std::vector<std::uint8_t> first;
  for (const fs::path& file : files) {
    const Mesh mesh = load_model(file);
    ASSERT_EQ(mesh.positions, kPositions) << file;
    ASSERT_EQ(mesh.indices, kIndices) << file;
    RenderJob job;
    job.model = file;
    job.width = 80;
    job.height = 60;
    job.outputs.color = fs::path(file).replace_extension(".png");
    render(job, renderer);
    int w = 0, h = 0;
    const std::vector<std::uint8_t> image = read_png(job.outputs.color, w, h);
    if (first.empty()) {
      first = image;
      // The pyramid fills part of the frame: the image is not all background.
      int drawn = 0;
      for (std::size_t i = 0; i < image.size(); i += 4) drawn += std::memcmp(&image[i], &image[0], 3) != 0;
      EXPECT_GT(drawn, 80 * 60 / 20);
    }
    EXPECT_EQ(image, first) << file << " draws another image than " << files[0];
  }
}

}  // namespace
}  // namespace facet::format_parity_tests
