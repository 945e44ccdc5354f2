// test_gltf_texcoord1.cpp - TEXCOORD_1: the glTF reader keeps the second uv set and which textures read it, and the
// physically based look samples each texture with its own set.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "facet/framebuffer.hpp"
#include "facet/image_io.hpp"
#include "facet/model_io.hpp"
#include "facet/renderer.hpp"
#include "facet/scene.hpp"
#include "facet/warnings.hpp"
#include "support/base64.hpp"
#include "support/load_problem.hpp"
#include "support/scratch_dir.hpp"

namespace facet::gltf_texcoord1_tests {
namespace {

namespace fs = std::filesystem;

// A 2 x 2 square facing +z whose TEXCOORD_0 is one point (0.25, 0.25) and whose TEXCOORD_1 spans [0, 1]^2; its
// material is black and rough, and emits a 2 x 2 PNG of four colours read through a NEAREST sampler (the base
// colour texture's, which facet uses for all of a material's textures), both textures reading set `texcoord`.
fs::path write_square(const std::string& name, int texcoord) {
  const std::string texture = R"({"index":0,"texCoord":)" + std::to_string(texcoord) + "}";
  const fs::path dir = test::scratch_dir("gltf_texcoord1");
  const std::vector<std::uint8_t> rgba = {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 255};
  write_png(dir / "four.png", 2, 2, rgba);
  const float positions[] = {-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0};
  const float uv0[] = {0.25f, 0.25f, 0.25f, 0.25f, 0.25f, 0.25f, 0.25f, 0.25f};
  const float uv1[] = {0, 1, 1, 1, 1, 0, 0, 0};
  const std::uint32_t indices[] = {0, 1, 2, 0, 2, 3};
  std::string buffer(sizeof positions + sizeof uv0 + sizeof uv1 + sizeof indices, '\0');
  char* at = buffer.data();
  for (const auto& [data, size] : {std::pair<const void*, std::size_t>{positions, sizeof positions},
                                   {uv0, sizeof uv0}, {uv1, sizeof uv1}, {indices, sizeof indices}}) {
    std::memcpy(at, data, size);
    at += size;
  }
  const std::string gltf =
      R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],)"
      R"("materials":[{"pbrMetallicRoughness":{"baseColorFactor":[0,0,0,1],"metallicFactor":0,"roughnessFactor":1,)"
      R"("baseColorTexture":)" +
      texture + R"(},"emissiveFactor":[1,1,1],"emissiveTexture":)" + texture +
      R"(}],"meshes":[{"primitives":[{"attributes":{"POSITION":0,"TEXCOORD_0":1,"TEXCOORD_1":2},"indices":3,)"
      R"("material":0}]}],)"
      R"("images":[{"uri":"four.png"}],"samplers":[{"magFilter":9728,"minFilter":9728}],)"
      R"("textures":[{"source":0,"sampler":0}],)"
      R"("accessors":[{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3","min":[-1,-1,0],"max":[1,1,0]},)"
      R"({"bufferView":1,"componentType":5126,"count":4,"type":"VEC2"},)"
      R"({"bufferView":2,"componentType":5126,"count":4,"type":"VEC2"},)"
      R"({"bufferView":3,"componentType":5125,"count":6,"type":"SCALAR"}],)"
      R"("bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":48},{"buffer":0,"byteOffset":48,"byteLength":32},)"
      R"({"buffer":0,"byteOffset":80,"byteLength":32},{"buffer":0,"byteOffset":112,"byteLength":24}],)"
      R"("buffers":[{"byteLength":136,"uri":"data:application/octet-stream;base64,)" +
      test::base64(buffer) + R"("}]})";
  return test::write_file(dir, name + ".gltf", gltf);
}

// The distinct colours of the square drawn head-on under the default look with no environment or light.
std::set<std::uint32_t> colours_of(const Mesh& mesh) {
  Scene scene;
  scene.add(Instance{std::make_shared<const Mesh>(mesh)});
  Renderer renderer(1);
  Framebuffer target(32, 32);
  const View view{glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, -3.0f)),
                  glm::perspective(0.8f, 1.0f, 0.1f, 20.0f)};
  SceneOptions options;
  options.tone_mapping = ToneMapping::none;
  scene.render(renderer, target, view, options);
  std::set<std::uint32_t> out;
  for (int y = 8; y < 24; ++y)
    for (int x = 8; x < 24; ++x) out.insert(target.pixel(x, y));
  return out;
}

TEST(GltfTexcoord1, TexturesReadTheSetTheyName) {
  WarningCapture warnings;
  const Mesh on_set0 = load_model(write_square("set0", 0));
  const Mesh on_set1 = load_model(write_square("set1", 1));
  EXPECT_TRUE(warnings.messages().empty()) << warnings.messages()[0];
  ASSERT_EQ(on_set1.uvs1.size(), 4u);
  // v flipped to facet's bottom-left origin, as the first set is.
  EXPECT_EQ(on_set1.uvs1[0], glm::vec2(0.0f, 0.0f));
  EXPECT_EQ(on_set1.uvs1[2], glm::vec2(1.0f, 1.0f));
  EXPECT_EQ(on_set0.materials.at(0).uv1_maps, 0u);
  EXPECT_EQ(on_set1.materials.at(0).uv1_maps, texture_slot::base_color | texture_slot::emissive);
  // The first set is one point: one texel everywhere. The second spans the texture: its four texels show.
  EXPECT_EQ(colours_of(on_set0).size(), 1u);
  EXPECT_EQ(colours_of(on_set1).size(), 4u);
}

// A set facet does not read is read as the first, with a warning naming it.
TEST(GltfTexcoord1, OtherSetsAreWarnedAbout) {
  WarningCapture warnings;
  const Mesh mesh = load_model(write_square("set2", 2));
  EXPECT_EQ(mesh.materials.at(0).uv1_maps, 0u);
  ASSERT_EQ(warnings.messages().size(), 2u);  // one per texture
  EXPECT_NE(warnings.messages()[0].find("reads TEXCOORD_2, which facet does not read; using TEXCOORD_0"),
            std::string::npos)
      << warnings.messages()[0];
}

// Khronos's BoxTexcoords (Debian's assimp-testmodels): the base colour on the first set, metallic-roughness on the
// second.
TEST(GltfTexcoord1, BoxTexcoordsKeepsBothSets) {
  const Mesh mesh = load_model("/usr/share/assimp/models/glTF2/BoxTexcoords-glTF/boxTexcoords.gltf");
  EXPECT_EQ(mesh.uvs1.size(), mesh.positions.size());
  EXPECT_EQ(mesh.uvs.size(), mesh.positions.size());
  ASSERT_EQ(mesh.materials.size(), 1u);
  EXPECT_EQ(mesh.materials[0].uv1_maps, texture_slot::metallic_roughness);
}

}  // namespace
}  // namespace facet::gltf_texcoord1_tests
