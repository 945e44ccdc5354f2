// test_gltf_loader.cpp - glTF 2.0 through load_model(): the three forms of one file, node transforms, real files.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "facet/error.hpp"
#include "facet/model_io.hpp"
#include "facet/texture.hpp"
#include "support/load_problem.hpp"
#include "support/scratch_dir.hpp"

namespace facet {
namespace {

namespace fs = std::filesystem;
const fs::path kGltf = "/usr/share/assimp/models/glTF2";

void expect_input_error(const fs::path& path, const std::string& problem) {
  const std::string got = test::load_problem(path);
  EXPECT_NE(got.find(problem), std::string::npos) << got;
}

TEST(GltfLoader, BoxTexturedIsTheSameMeshInEveryForm) {
  const Mesh separate = load_model(kGltf / "BoxTextured-glTF/BoxTextured.gltf");
  const Mesh binary = load_model(kGltf / "BoxTextured-glTF-Binary/BoxTextured.glb");
  const Mesh embedded = load_model(kGltf / "BoxTextured-glTF-Embedded/BoxTextured.gltf");
  EXPECT_EQ(separate.vertex_count(), 24u);
  EXPECT_EQ(separate.triangle_count(), 12u);
  ASSERT_EQ(separate.normals.size(), 24u);
  ASSERT_EQ(separate.uvs.size(), 24u);
  for (const Mesh* m : {&binary, &embedded}) {
    EXPECT_EQ(m->positions, separate.positions);
    EXPECT_EQ(m->normals, separate.normals);
    EXPECT_EQ(m->uvs, separate.uvs);
    EXPECT_EQ(m->indices, separate.indices);
    ASSERT_EQ(m->materials.size(), 1u);
    ASSERT_TRUE(m->materials[0].diffuse_map);
    EXPECT_EQ(m->materials[0].diffuse_map->width(), separate.materials[0].diffuse_map->width());
  }
  // The box's node turns it -90 degrees about X (a Z-up to Y-up matrix), so its unit extent stays but moves axes.
  for (const glm::vec3& p : separate.positions) EXPECT_NEAR(std::abs(p.y), 0.5f, 1e-6f);
  EXPECT_EQ(separate.face_materials, std::vector<std::int32_t>(12, 0));
}

TEST(GltfLoader, ContentDecidesWhereTheExtensionIsWrong) {
  const fs::path dir = test::scratch_dir("gltf");
  fs::copy_file(kGltf / "BoxTextured-glTF-Binary/BoxTextured.glb", dir / "box.model");
  EXPECT_EQ(load_model(dir / "box.model").triangle_count(), 12u);
  fs::copy_file(kGltf / "BoxTextured-glTF-Embedded/BoxTextured.gltf", dir / "box.txt");
  EXPECT_EQ(load_model(dir / "box.txt").triangle_count(), 12u);
}

TEST(GltfLoader, MalformedFilesAreRefusedWithTheirProblem) {
  expect_input_error(kGltf / "IndexOutOfRange/IndexOutOfRange.gltf", "out of range");
  expect_input_error(kGltf / "BoxWithInfinites-glTF-Binary/BoxWithInfinites.glb", "finite");
  expect_input_error(kGltf / "RecursiveNodes/RecursiveNodes.gltf", "ancestor");
  const fs::path dir = test::scratch_dir("gltf");
  std::ofstream(dir / "required.gltf")
      << R"({"asset":{"version":"2.0"},"extensionsUsed":["EXT_unknown"],"extensionsRequired":["EXT_unknown"]})";
  expect_input_error(dir / "required.gltf", "EXT_unknown");
  std::ofstream(dir / "empty_scene.gltf") << R"({"asset":{"version":"2.0"},"scenes":[{"nodes":[]}],"scene":0})";
  expect_input_error(dir / "empty_scene.gltf", "no triangles");
  std::ofstream(dir / "broken.gltf") << R"({"asset":{"version":"2.0"},"nodes":[{"mesh":0)";
  expect_input_error(dir / "broken.gltf", "");
  std::ofstream(dir / "cut.glb", std::ios::binary) << std::string("glTF\x02\0\0\0\xff\xff\0\0", 12);
  expect_input_error(dir / "cut.glb", "");
}

// Every glTF file Debian ships either loads (at least one triangle, validated) or is refused with InputError.
TEST(GltfLoader, EveryAssimpModelLoadsOrThrowsInputError) {
  int loaded = 0, refused = 0;
  for (const auto& entry : fs::recursive_directory_iterator(kGltf)) {
    const std::string ext = entry.path().extension().string();
    if (ext != ".gltf" && ext != ".glb") continue;
    try {
      const Mesh m = load_model(entry.path());
      EXPECT_GT(m.triangle_count(), 0u) << entry.path();
      ++loaded;
    } catch (const InputError& e) {
      EXPECT_EQ(e.source(), entry.path().string());
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
      ++refused;
    }
  }
  EXPECT_GT(loaded, 20);
  EXPECT_GT(refused, 3);
}

}  // namespace
}  // namespace facet
