// test_gltf_loader.cpp - glTF 2.0 through load_model(): the three forms of one file, node transforms, real files.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <string>

#include "facet/color.hpp"
#include "facet/error.hpp"
#include "facet/mesh.hpp"
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

// The triangles a glTF file's default scene declares: its nodes' meshes' index counts / 3, node by node.
std::size_t declared_triangles(const nlohmann::json& gltf, int node) {
  const nlohmann::json& n = gltf["nodes"][static_cast<std::size_t>(node)];
  std::size_t triangles = 0;
  if (n.contains("mesh"))
    for (const nlohmann::json& p : gltf["meshes"][n["mesh"].get<std::size_t>()]["primitives"])
      triangles += gltf["accessors"][p["indices"].get<std::size_t>()]["count"].get<std::size_t>() / 3;
  if (n.contains("children"))
    for (const nlohmann::json& child : n["children"]) triangles += declared_triangles(gltf, child.get<int>());
  return triangles;
}

// KHR_draco_mesh_compression: the Draco copy of 2CylinderEngine decodes to the triangles its accessors declare
// (its encoder dropped the plain file's degenerate ones), its positions within Draco's quantization of the plain
// file's.
TEST(GltfLoader, DracoMeshesDecodeToThePlainFilesGeometry) {
  const fs::path file = kGltf / "draco/2CylinderEngine.gltf";
  const Mesh draco = load_model(file);
  const Mesh plain = load_model(kGltf / "2CylinderEngine-glTF-Binary/2CylinderEngine.glb");
  std::ifstream in(file);
  const nlohmann::json gltf = nlohmann::json::parse(in);
  std::size_t declared = 0;
  for (const nlohmann::json& root : gltf["scenes"][gltf["scene"].get<std::size_t>()]["nodes"])
    declared += declared_triangles(gltf, root.get<int>());
  EXPECT_EQ(draco.triangle_count(), declared);
  EXPECT_LT(draco.triangle_count(), plain.triangle_count());
  EXPECT_EQ(draco.normals.size(), draco.positions.size());
  const Bounds a = bounds(draco), b = bounds(plain);
  const float tolerance = 1e-3f * glm::length(b.max - b.min);
  for (int axis = 0; axis < 3; ++axis) {
    EXPECT_NEAR(a.min[axis], b.min[axis], tolerance);
    EXPECT_NEAR(a.max[axis], b.max[axis], tolerance);
  }
  // A compressed view that is not Draco data is refused, naming the extension's problem.
  const fs::path dir = test::scratch_dir("gltf");
  std::ofstream(dir / "not_draco.gltf")
      << R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],)"
         R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"extensions":{"KHR_draco_mesh_compression":)"
         R"({"bufferView":0,"attributes":{"POSITION":0}}}}]}],)"
         R"("accessors":[{"componentType":5126,"count":3,"type":"VEC3"}],)"
         R"("bufferViews":[{"buffer":0,"byteLength":8}],)"
         R"("buffers":[{"byteLength":8,"uri":"data:application/octet-stream;base64,AAAAAAAAAAA="}]})";
  expect_input_error(dir / "not_draco.gltf", "Draco");
}

// KHR_texture_transform moves TEXCOORD_0 by offset, rotation and scale (T * R * S, the extension's definition);
// glTF samplers become the materials' filtering and wrapping. The same file without the extension is the baseline.
TEST(GltfLoader, TextureTransformsAndSamplersFollowTheFile) {
  const fs::path source = kGltf / "textureTransform";
  const fs::path dir = test::scratch_dir("gltf_transform");
  for (const char* name :
       {"TextureTransformTest.bin", "Arrow.png", "Correct.png", "Error.png", "NotSupported.png", "UV.png"})
    fs::copy_file(source / name, dir / name, fs::copy_options::overwrite_existing);
  std::ifstream in(source / "TextureTransformTest.gltf");
  std::string json((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  // Without the extension: each texture reference's "extensions" object names only KHR_texture_transform.
  std::string plain = json;
  for (std::size_t at; (at = plain.find("\"KHR_texture_transform\" :")) != std::string::npos ||
                       (at = plain.find("\"KHR_texture_transform\":")) != std::string::npos;)
    plain.replace(at, 2, "\"x");  // renames the key: an unknown extension is ignored
  std::ofstream(dir / "plain.gltf") << plain;
  const Mesh transformed = load_model(source / "TextureTransformTest.gltf");
  const Mesh baseline = load_model(dir / "plain.gltf");
  ASSERT_EQ(transformed.uvs.size(), baseline.uvs.size());
  ASSERT_EQ(transformed.face_materials, baseline.face_materials);
  ASSERT_GE(transformed.materials.size(), 6u);

  struct Expected {
    glm::vec2 offset{0.0f};
    float rotation = 0.0f;
    glm::vec2 scale{1.0f};
  };
  const Expected expected[6] = {{{0.5f, 0.0f}},           {{0.0f, 0.5f}},
                                {{0.5f, 0.5f}},           {{}, 0.39269908169872414f},
                                {{}, 0.0f, {1.5f, 1.5f}}, {{-0.2f, -0.1f}, 0.3f, {1.5f, 1.5f}}};
  // The flattened mesh numbers materials in order of first use; the file's order is known by name.
  const std::string names[6] = {"Offset U", "Offset V", "Offset UV", "Rotation", "Scale", "All"};
  const auto file_index = [&](std::int32_t m) {
    if (m < 0) return -1;
    const auto found = std::find(std::begin(names), std::end(names), transformed.materials[m].name);
    return found == std::end(names) ? -1 : static_cast<int>(found - std::begin(names));
  };
  std::size_t checked = 0;
  for (std::size_t t = 0; t < transformed.face_materials.size(); ++t) {
    const int m = file_index(transformed.face_materials[t]);
    if (m < 0) continue;
    const Expected& e = expected[m];
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t v = transformed.indices[3 * t + k];
      // Both meshes hold v flipped to a bottom-left origin; the transform applies to glTF's (u, 1 - v).
      const glm::vec2 uv = glm::vec2(baseline.uvs[v].x, 1.0f - baseline.uvs[v].y) * e.scale;
      const float c = std::cos(e.rotation), s = std::sin(e.rotation);
      const glm::vec2 moved = glm::vec2(c * uv.x + s * uv.y, -s * uv.x + c * uv.y) + e.offset;
      const glm::vec2 want(moved.x, 1.0f - moved.y);
      EXPECT_NEAR(transformed.uvs[v].x, want.x, 1e-5f) << "material " << m;
      EXPECT_NEAR(transformed.uvs[v].y, want.y, 1e-5f) << "material " << m;
      ++checked;
    }
  }
  EXPECT_GE(checked, 6u * 6u);  // two triangles per transformed square at least

  // Textures 0 and 1 use sampler 0 (CLAMP_TO_EDGE, LINEAR); the marker textures have no sampler.
  std::size_t transformed_materials = 0;
  for (std::size_t m = 0; m < transformed.materials.size(); ++m) {
    if (file_index(static_cast<std::int32_t>(m)) < 0) continue;
    ++transformed_materials;
    ASSERT_TRUE(transformed.materials[m].sampler) << m;
    EXPECT_EQ(transformed.materials[m].sampler->wrap_u, Wrap::clamp);
    EXPECT_EQ(transformed.materials[m].sampler->wrap_v, Wrap::clamp);
    EXPECT_EQ(transformed.materials[m].sampler->filter, Filter::bilinear);
  }
  EXPECT_EQ(transformed_materials, 6u);
  for (std::size_t m = 0; m < transformed.materials.size(); ++m)
    if (file_index(static_cast<std::int32_t>(m)) < 0) {
      EXPECT_FALSE(transformed.materials[m].sampler) << m;
    }
}

// KHR_materials_unlit marks its material unlit (the scene then draws it with its colour alone), and is accepted
// in extensionsRequired; the file's other material stays lit.
TEST(GltfLoader, UnlitMaterialsAreMarked) {
  const fs::path dir = test::scratch_dir("gltf_unlit");
  std::ofstream(dir / "unlit.gltf")
      << R"({"asset":{"version":"2.0"},"extensionsUsed":["KHR_materials_unlit"],"extensionsRequired":["KHR_materials_unlit"],"buffers":[{"byteLength":36,"uri":"data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}],"bufferViews":[{"buffer":0,"byteLength":36}],"accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]}],"materials":[{"pbrMetallicRoughness":{"baseColorFactor":[0.2,0.6,0.4,1]},"extensions":{"KHR_materials_unlit":{}}},{}],"meshes":[{"primitives":[{"attributes":{"POSITION":0},"material":0},{"attributes":{"POSITION":0},"material":1}]}],"nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}],"scene":0})";
  const Mesh mesh = load_model(dir / "unlit.gltf");
  ASSERT_EQ(mesh.materials.size(), 2u);
  EXPECT_TRUE(mesh.materials[0].unlit);
  EXPECT_FALSE(mesh.materials[1].unlit);
  EXPECT_EQ(mesh.materials[0].diffuse, linear_to_srgb(glm::vec4(0.2f, 0.6f, 0.4f, 1.0f)));  // as displayed
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
