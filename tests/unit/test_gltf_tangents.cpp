// test_gltf_tangents.cpp - glTF TANGENT: the reader keeps unit tangents and their handedness, and the physically
// based look takes a normal map's frame from them.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "facet/framebuffer.hpp"
#include "facet/image_io.hpp"
#include "facet/model_io.hpp"
#include "facet/renderer.hpp"
#include "facet/scene.hpp"
#include "support/base64.hpp"
#include "support/load_problem.hpp"
#include "support/scratch_dir.hpp"

namespace facet::gltf_tangents_tests {
namespace {

namespace fs = std::filesystem;

// A 2 x 2 square facing +z, u along +x and v (facet's, bottom-up) along +y, white, rough and non-metallic, its
// normal map one texel of `texel`. `tangent` is every vertex's TANGENT (none when unset), of accessor type
// `tangent_type`; `node` the square's node (its transform).
struct Square {
  glm::u8vec3 texel{128, 128, 255};
  std::optional<glm::vec4> tangent;
  std::string tangent_type = "VEC4";
  bool normals = true;
  std::string node = R"({"mesh":0})";
};

fs::path write_square(const std::string& name, const Square& square) {
  const fs::path dir = test::scratch_dir("gltf_tangents");
  const std::vector<std::uint8_t> rgba = {square.texel.r, square.texel.g, square.texel.b, 255};
  write_png(dir / (name + ".png"), 1, 1, rgba);
  std::vector<float> floats = {-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0};  // positions
  const std::vector<float> normals = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
  const std::vector<float> uvs = {0, 1, 1, 1, 1, 0, 0, 0};  // glTF's v grows downwards
  std::string attributes = R"("POSITION":0)", accessors =
      R"({"bufferView":0,"componentType":5126,"count":4,"type":"VEC3","min":[-1,-1,0],"max":[1,1,0]})";
  std::string views = R"({"buffer":0,"byteOffset":0,"byteLength":48})";
  int next = 1;
  const auto add = [&](const char* attribute, const std::vector<float>& values, const std::string& type) {
    const std::size_t offset = floats.size() * sizeof(float);
    floats.insert(floats.end(), values.begin(), values.end());
    attributes += R"(,")" + std::string(attribute) + R"(":)" + std::to_string(next);
    accessors += R"(,{"bufferView":)" + std::to_string(next) + R"(,"componentType":5126,"count":4,"type":")" + type +
                 R"("})";
    views += R"(,{"buffer":0,"byteOffset":)" + std::to_string(offset) + R"(,"byteLength":)" +
             std::to_string(values.size() * sizeof(float)) + "}";
    ++next;
  };
  if (square.normals) add("NORMAL", normals, "VEC3");
  add("TEXCOORD_0", uvs, "VEC2");
  if (square.tangent) {
    std::vector<float> tangents;
    const std::size_t components = square.tangent_type == "VEC4" ? 4 : 3;
    for (int v = 0; v < 4; ++v)
      for (std::size_t c = 0; c < components; ++c) tangents.push_back((*square.tangent)[static_cast<int>(c)]);
    add("TANGENT", tangents, square.tangent_type);
  }
  const std::uint32_t indices[] = {0, 1, 2, 0, 2, 3};
  std::string buffer(floats.size() * sizeof(float) + sizeof indices, '\0');
  std::memcpy(buffer.data(), floats.data(), floats.size() * sizeof(float));
  std::memcpy(buffer.data() + floats.size() * sizeof(float), indices, sizeof indices);
  accessors += R"(,{"bufferView":)" + std::to_string(next) + R"(,"componentType":5125,"count":6,"type":"SCALAR"})";
  views += R"(,{"buffer":0,"byteOffset":)" + std::to_string(floats.size() * sizeof(float)) + R"(,"byteLength":24})";
  const std::string gltf =
      R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[)" + square.node + "],"
      R"("materials":[{"pbrMetallicRoughness":{"metallicFactor":0,"roughnessFactor":1},)"
      R"("normalTexture":{"index":0}}],)"
      R"("meshes":[{"primitives":[{"attributes":{)" + attributes + R"(},"indices":)" + std::to_string(next) +
      R"(,"material":0}]}],)"
      R"("images":[{"uri":")" + name + R"(.png"}],"textures":[{"source":0}],)"
      R"("accessors":[)" + accessors + R"(],"bufferViews":[)" + views + "],"
      R"("buffers":[{"byteLength":)" + std::to_string(buffer.size()) +
      R"(,"uri":"data:application/octet-stream;base64,)" + test::base64(buffer) + R"("}]})";
  return test::write_file(dir, name + ".gltf", gltf);
}

TEST(GltfTangents, AreReadAsUnitVectorsWithTheirHandedness) {
  Square square;
  square.tangent = glm::vec4(2.0f, 0.0f, 0.0f, -0.5f);
  const Mesh mesh = load_model(write_square("read", square));
  ASSERT_EQ(mesh.tangents.size(), 4u);
  for (const glm::vec4& t : mesh.tangents) EXPECT_EQ(t, glm::vec4(1.0f, 0.0f, 0.0f, -1.0f));
}

TEST(GltfTangents, FollowTheNodeAndTurnWithAMirror) {
  Square square;
  square.tangent = glm::vec4(1.0f, 0.0f, 0.0f, 1.0f);
  // Mirrored in x, then turned a quarter about z (glTF applies scale, then rotation): +x goes to -x, then to -y.
  square.node = R"({"mesh":0,"rotation":[0,0,0.7071068,0.7071068],"scale":[-1,1,1]})";
  const Mesh mesh = load_model(write_square("mirrored", square));
  ASSERT_EQ(mesh.tangents.size(), 4u);
  for (const glm::vec4& t : mesh.tangents) {
    EXPECT_NEAR(glm::length(glm::vec3(t) - glm::vec3(0.0f, -1.0f, 0.0f)), 0.0f, 1e-6f) << t.x << "," << t.y;
    EXPECT_EQ(t.w, -1.0f);
  }
}

TEST(GltfTangents, AreDroppedWithoutNormalsAndRefusedOfTheWrongType) {
  Square square;
  square.tangent = glm::vec4(1.0f, 0.0f, 0.0f, 1.0f);
  square.normals = false;
  EXPECT_TRUE(load_model(write_square("no_normals", square)).tangents.empty());
  Square three;
  three.tangent = glm::vec4(1.0f, 0.0f, 0.0f, 1.0f);
  three.tangent_type = "VEC3";
  const std::string problem = test::load_problem(write_square("vec3", three));
  EXPECT_NE(problem.find("TANGENT"), std::string::npos) << problem;
  EXPECT_NE(problem.find("wrong type"), std::string::npos) << problem;
}

// The square's middle pixel (red channel, as displayed) under one directional light from `towards` alone.
int lit(const Square& square, const std::string& name, glm::vec3 towards) {
  Scene scene;
  scene.add(Instance{std::make_shared<const Mesh>(load_model(write_square(name, square)))});
  Renderer renderer(1);
  Framebuffer target(16, 16);
  const View view{glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, -3.0f)),
                  glm::perspective(0.8f, 1.0f, 0.1f, 20.0f)};
  SceneOptions options;
  Light light;
  light.vector = glm::normalize(towards);
  light.intensity = 2.0f;
  options.lights = {light};
  options.ambient = glm::vec3(0.0f);
  options.tone_mapping = ToneMapping::none;
  scene.render(renderer, target, view, options);
  renderer.finish(target);
  return static_cast<int>(target.pixel(8, 8) & 0xFF);
}

// A texel tilting the normal 45 degrees towards the tangent (red) or the bitangent (green): lit by a light on that
// side, dark when the tangent or its handedness says the other side. Tangents along the uvs give the cotangent
// frame's picture.
TEST(GltfTangents, GiveTheNormalMapItsFrame) {
  Square towards_u;
  towards_u.texel = {218, 128, 218};
  const int without = lit(towards_u, "u_none", {1, 0, 1});
  towards_u.tangent = glm::vec4(1.0f, 0.0f, 0.0f, 1.0f);
  const int along = lit(towards_u, "u_along", {1, 0, 1});
  towards_u.tangent = glm::vec4(-1.0f, 0.0f, 0.0f, 1.0f);
  const int against = lit(towards_u, "u_against", {1, 0, 1});
  EXPECT_GT(without, 150);
  EXPECT_NEAR(along, without, 2);
  EXPECT_LT(against, without - 80);

  Square towards_v;
  towards_v.texel = {128, 218, 218};
  const int v_without = lit(towards_v, "v_none", {0, 1, 1});
  towards_v.tangent = glm::vec4(1.0f, 0.0f, 0.0f, 1.0f);
  const int right_handed = lit(towards_v, "v_right", {0, 1, 1});
  towards_v.tangent = glm::vec4(1.0f, 0.0f, 0.0f, -1.0f);
  const int left_handed = lit(towards_v, "v_left", {0, 1, 1});
  EXPECT_GT(v_without, 150);
  EXPECT_NEAR(right_handed, v_without, 2);
  EXPECT_LT(left_handed, v_without - 80);
}

}  // namespace
}  // namespace facet::gltf_tangents_tests
