// test_gltf_animation.cpp - glTF skins, morph targets and animations against an oracle that reads the JSON itself.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "facet/error.hpp"
#include "facet/model.hpp"
#include "facet/model_io.hpp"
#include "facet/render_job.hpp"
#include "facet/warnings.hpp"
#include "support/base64.hpp"
#include "support/gltf_square.hpp"
#include "support/load_problem.hpp"
#include "support/scratch_dir.hpp"

namespace facet::gltf_animation_tests {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;
const fs::path kGltf = "/usr/share/assimp/models/glTF2";

// The oracle: a glTF file read with nlohmann's JSON and plain byte copies, without tinygltf or facet's reader, and
// posed with glm's own slerp and mix, node by node as the glTF specification describes it.
struct Oracle {
  Json json;
  std::vector<std::string> buffers;

  explicit Oracle(const fs::path& path) {
    std::ifstream in(path);
    json = Json::parse(in);
    for (const Json& b : json["buffers"]) {
      const std::string uri = b["uri"];
      const auto comma = uri.find(',');
      if (uri.starts_with("data:")) {
        buffers.push_back(decode_base64(uri.substr(comma + 1)));
      } else {
        std::ifstream bin(path.parent_path() / uri, std::ios::binary);
        buffers.emplace_back(std::istreambuf_iterator<char>(bin), std::istreambuf_iterator<char>());
      }
    }
  }

  static std::string decode_base64(const std::string& text) {
    std::string out;
    std::uint32_t bits = 0;
    int count = 0;
    for (const char c : text) {
      const char* digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
      const char* at = std::strchr(digits, c);
      if (c == '=' || !at) continue;
      bits = bits << 6 | static_cast<std::uint32_t>(at - digits);
      if ((count += 6) >= 8) out += static_cast<char>(bits >> (count -= 8) & 0xFF);
    }
    return out;
  }

  // Accessor `index` as floats, `n` components an element (float, unsigned byte or unsigned short components).
  std::vector<float> floats(int index, int n) const {
    const Json& a = json["accessors"][index];
    const Json& view = json["bufferViews"][a["bufferView"].get<int>()];
    const int type = a["componentType"];
    const std::size_t size = type == 5126 ? 4 : type == 5123 ? 2 : 1;
    const std::size_t stride = view.value("byteStride", size * n);
    const std::string& buffer = buffers[view["buffer"].get<std::size_t>()];
    const std::size_t start = view.value("byteOffset", 0u) + a.value("byteOffset", 0u);
    std::vector<float> out;
    for (std::size_t i = 0; i < a["count"].get<std::size_t>(); ++i)
      for (int c = 0; c < n; ++c) {
        const char* p = buffer.data() + start + i * stride + c * size;
        if (type == 5126) {
          float v;
          std::memcpy(&v, p, 4);
          out.push_back(v);
        } else if (type == 5123) {
          std::uint16_t v;
          std::memcpy(&v, p, 2);
          out.push_back(v);
        } else {
          out.push_back(static_cast<unsigned char>(*p));
        }
      }
    return out;
  }

  // Animation 0's sampler `s` at time t, linear: the keys around t mixed (quaternions slerped by glm).
  std::vector<float> sampled(int s, float t, int n) const {
    const Json& sampler = json["animations"][0]["samplers"][s];
    const std::vector<float> times = floats(sampler["input"], 1);
    const std::vector<float> values = floats(sampler["output"], n == 0 ? 1 : n);
    const std::size_t width = n == 0 ? values.size() / times.size() : static_cast<std::size_t>(n);
    std::size_t k = 0;
    while (k + 1 < times.size() && times[k + 1] <= t) ++k;
    const std::size_t next = std::min(k + 1, times.size() - 1);
    const float u = next == k ? 0.0f : std::clamp((t - times[k]) / (times[next] - times[k]), 0.0f, 1.0f);
    std::vector<float> out(width);
    if (width == 4) {
      const glm::quat a(values[4 * k + 3], values[4 * k], values[4 * k + 1], values[4 * k + 2]);
      const glm::quat b(values[4 * next + 3], values[4 * next], values[4 * next + 1], values[4 * next + 2]);
      // Keys are stored to three decimals (simple_skin's 0.383, 0.924), a little off unit length: normalised, as
      // glTF's rotations are unit quaternions.
      const glm::quat q = glm::normalize(glm::slerp(a, b, u));
      out = {q.x, q.y, q.z, q.w};
    } else {
      for (std::size_t c = 0; c < width; ++c) out[c] = glm::mix(values[k * width + c], values[next * width + c], u);
    }
    return out;
  }

  glm::mat4 world(int node, float t) const {
    const Json& n = json["nodes"][node];
    glm::vec3 translation(0.0f), scale(1.0f);
    glm::quat rotation(1, 0, 0, 0);
    if (n.contains("translation")) translation = {n["translation"][0], n["translation"][1], n["translation"][2]};
    if (n.contains("scale")) scale = {n["scale"][0], n["scale"][1], n["scale"][2]};
    if (n.contains("rotation"))
      rotation = glm::quat(n["rotation"][3], n["rotation"][0], n["rotation"][1], n["rotation"][2]);
    for (const Json& channel : json["animations"][0]["channels"]) {
      if (channel["target"]["node"] != node) continue;
      const std::string path = channel["target"]["path"];
      if (path == "rotation") {
        const std::vector<float> q = sampled(channel["sampler"], t, 4);
        rotation = glm::quat(q[3], q[0], q[1], q[2]);
      } else if (path == "translation") {
        const std::vector<float> v = sampled(channel["sampler"], t, 3);
        translation = {v[0], v[1], v[2]};
      }
    }
    const glm::mat4 local =
        glm::translate(glm::mat4(1.0f), translation) * glm::mat4_cast(rotation) * glm::scale(glm::mat4(1.0f), scale);
    const Json& nodes = json["nodes"];
    for (std::size_t p = 0; p < nodes.size(); ++p)
      for (const Json& child : nodes[p].value("children", Json::array()))
        if (child == node) return world(static_cast<int>(p), t) * local;
    return local;
  }
};

// What facet draws of the file at t: its animation 0 posed and flattened.
Mesh drawn(const fs::path& path, float t) { return flatten(pose(read_model(path), 0, t, path.string()), path); }

TEST(GltfAnimation, SimpleSkinBendsAsTheOracleSkinsIt) {
  const fs::path path = kGltf / "simple_skin/simple_skin.gltf";
  const Oracle oracle(path);
  const Json& primitive = oracle.json["meshes"][0]["primitives"][0];
  const std::vector<float> p = oracle.floats(primitive["attributes"]["POSITION"], 3);
  const std::vector<float> j = oracle.floats(primitive["attributes"]["JOINTS_0"], 4);
  const std::vector<float> w = oracle.floats(primitive["attributes"]["WEIGHTS_0"], 4);
  const std::vector<float> ibm = oracle.floats(oracle.json["skins"][0]["inverseBindMatrices"], 16);
  const Json& joints = oracle.json["skins"][0]["joints"];
  double moved = 0.0;
  for (const float t : {0.0f, 0.7f, 1.25f, 2.0f, 3.3f, 5.5f}) {
    const Mesh mesh = drawn(path, t);
    ASSERT_EQ(mesh.vertex_count(), p.size() / 3);
    for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
      glm::mat4 skin(0.0f);
      for (int k = 0; k < 4; ++k) {
        const int joint = static_cast<int>(j[4 * v + k]);
        skin += w[4 * v + k] * oracle.world(joints[joint], t) * glm::make_mat4(ibm.data() + 16 * joint);
      }
      const glm::vec3 want(skin * glm::vec4(p[3 * v], p[3 * v + 1], p[3 * v + 2], 1.0f));
      EXPECT_NEAR(glm::length(mesh.positions[v] - want), 0.0f, 1e-5f) << "t " << t << " vertex " << v;
      moved += glm::length(want - glm::vec3(p[3 * v], p[3 * v + 1], p[3 * v + 2]));
    }
  }
  EXPECT_GT(moved, 1.0);  // the skin does bend: the comparison is not of rest poses
}

TEST(GltfAnimation, AnimatedMorphCubeBlendsItsTargetsAsTheOracleDoes) {
  const fs::path path = kGltf / "glTF-Sample-Models/AnimatedMorphCube-glTF/AnimatedMorphCube.gltf";
  const Oracle oracle(path);
  const Json& primitive = oracle.json["meshes"][0]["primitives"][0];
  const std::vector<float> base = oracle.floats(primitive["attributes"]["POSITION"], 3);
  const Model model = read_model(path);
  ASSERT_EQ(model.animations.size(), 1u);
  EXPECT_EQ(model.animations[0].name, "Square");
  ASSERT_EQ(model.deformations.size(), 1u);
  ASSERT_EQ(model.deformations[0].morph_targets.size(), primitive["targets"].size());
  for (const float t : {0.0f, 0.4f, 1.1f, 2.5f, 3.9f}) {
    const std::vector<float> weights = oracle.sampled(0, t, 0);
    const glm::mat4 world = oracle.world(0, t);
    const Mesh mesh = drawn(path, t);
    ASSERT_EQ(mesh.vertex_count(), base.size() / 3);
    for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
      glm::vec3 want(base[3 * v], base[3 * v + 1], base[3 * v + 2]);
      for (std::size_t k = 0; k < weights.size(); ++k) {
        const std::vector<float> d = oracle.floats(primitive["targets"][k]["POSITION"], 3);
        want += weights[k] * glm::vec3(d[3 * v], d[3 * v + 1], d[3 * v + 2]);
      }
      want = glm::vec3(world * glm::vec4(want, 1.0f));
      EXPECT_NEAR(glm::length(mesh.positions[v] - want), 0.0f, 1e-5f) << "t " << t << " vertex " << v;
    }
  }
}

// The square of gltf_square.hpp with an animation of node 0 whose sampler reads accessors 2 (times) and 3 (values)
// from a second buffer holding `times` and `values`.
std::string animated_square(const std::vector<float>& times, const std::vector<float>& values, const std::string& path,
                            const std::string& type, int time_count, int value_count,
                            const std::string& interpolation = "LINEAR", int node = 0, const std::string& nodes = "",
                            int node_count = 0, const std::string& top_level = "") {
  std::string buffer(4 * (times.size() + values.size()), '\0');
  std::memcpy(buffer.data(), times.data(), 4 * times.size());
  std::memcpy(buffer.data() + 4 * times.size(), values.data(), 4 * values.size());
  std::string file = test::square_gltf(nodes, node_count, top_level);
  // Accessors 2 and 3, buffer view 2 and 3 in buffer 1.
  const auto insert_before = [&](const std::string& marker, const std::string& text) {
    const auto at = file.find(marker);
    file.insert(at, text);
  };
  insert_before(R"(],"bufferViews")", R"(,{"bufferView":2,"componentType":5126,"count":)" + std::to_string(time_count) +
                                          R"(,"type":"SCALAR"},{"bufferView":3,"componentType":5126,"count":)" +
                                          std::to_string(value_count) + R"(,"type":")" + type + R"("})");
  insert_before(R"(],"buffers")", R"(,{"buffer":1,"byteOffset":0,"byteLength":)" + std::to_string(4 * times.size()) +
                                      R"(},{"buffer":1,"byteOffset":)" + std::to_string(4 * times.size()) +
                                      R"(,"byteLength":)" + std::to_string(4 * values.size()) + "}");
  file.insert(file.size() - 2, R"(,{"byteLength":)" + std::to_string(buffer.size()) +
                                   R"(,"uri":"data:application/octet-stream;base64,)" + test::base64(buffer) + R"("})");
  file.insert(file.size() - 1, R"(,"animations":[{"name":"Slide","samplers":[{"input":2,"output":3,"interpolation":")" +
                                   interpolation + R"("}],"channels":[{"sampler":0,"target":{"node":)" +
                                   std::to_string(node) + R"(,"path":")" + path + R"("}}]}])");
  return file;
}

TEST(GltfAnimation, AnimationsOfMalformedDataAreLeftOutWithAWarning) {
  const fs::path dir = test::scratch_dir("gltf_animation");
  const auto warnings_of = [&](const std::string& file, std::size_t* animations) {
    const fs::path path = test::write_file(dir, "a.gltf", file);
    WarningCapture capture;
    *animations = read_model(path).animations.size();
    std::string all;
    for (const std::string& w : capture.messages()) all += w + "\n";
    return all;
  };
  std::size_t count = 0;
  // A good animation: read, no warning; at 0.5 s the square has slid half way.
  const std::string good = animated_square({0, 1}, {0, 0, 0, 2, 0, 0}, "translation", "VEC3", 2, 2);
  EXPECT_EQ(warnings_of(good, &count), "");
  EXPECT_EQ(count, 1u);
  const fs::path path = test::write_file(dir, "good.gltf", good);
  EXPECT_NEAR(drawn(path, 0.5f).positions[0].x, 0.0f, 1e-6f);  // -1 + 1
  const struct {
    std::string file, problem;
  } cases[] = {
      {animated_square({1, 1}, {0, 0, 0, 2, 0, 0}, "translation", "VEC3", 2, 2), "key times do not increase"},
      {animated_square({0, NAN}, {0, 0, 0, 2, 0, 0}, "translation", "VEC3", 2, 2), "not a finite number"},
      {animated_square({0, 1}, {0, 0, 0, 2, 0, INFINITY}, "translation", "VEC3", 2, 2), "value 5 is not a finite"},
      {animated_square({0, 1}, {0, 0, 0, 2, 0, 0}, "translation", "VEC3", 2, 3), "does not fit in its buffer view"},
      {animated_square({0, 1}, {0, 0, 0, 2, 0, 0}, "translation", "VEC3", 2, 1), "has 3 values for 2 keys of 3"},
      {animated_square({0, 1}, {0, 0, 0, 2, 0, 0, 0, 0}, "rotation", "VEC4", 2, 2, "LINEAR"), ""},
      {animated_square({0, 1}, {0, 0, 0, 2, 0, 0}, "rotation", "VEC3", 2, 2), "has keys of 3 values, not 4"},
      {animated_square({0, 1}, {0, 0, 0, 2, 0, 0}, "translation", "VEC3", 2, 2, "BOUNCE"), "unknown interpolation"},
      {animated_square({0, 1}, {0, 0, 0, 2, 0, 0}, "translation", "VEC3", 2, 2, "LINEAR", 4), "node 4, which does"},
      {animated_square({0, 1}, {0, 1}, "weights", "SCALAR", 2, 2), "has keys of 1 values, not 0"},
  };
  for (const auto& c : cases) {
    const std::string warnings = warnings_of(c.file, &count);
    if (c.problem.empty()) continue;
    EXPECT_EQ(count, 0u) << c.problem;
    EXPECT_NE(warnings.find(c.problem), std::string::npos) << warnings;
    EXPECT_EQ(warnings.find("animation 0 'Slide' is left out: "), warnings.find(": ") + 2) << warnings;
    // The model itself still loads and draws, unanimated.
    const WarningCapture quiet;
    EXPECT_EQ(load_model(test::write_file(dir, "bad.gltf", c.file)).vertex_count(), 4u);
  }
}

TEST(GltfAnimation, CamerasAndLightsFollowTheirAnimatedNodes) {
  const fs::path dir = test::scratch_dir("gltf_camera_motion");
  // Node 1 holds a camera and a spot light; its translation slides from (0, 0, 5) to (2, 0, 5) over 1 s.
  const std::string file =
      animated_square({0, 1}, {0, 0, 5, 2, 0, 5}, "translation", "VEC3", 2, 2, "LINEAR", 1,
                      R"({"camera":0,"translation":[0,0,5],"extensions":{"KHR_lights_punctual":{"light":0}}})", 1,
                      R"(,"cameras":[{"type":"perspective","perspective":{"yfov":0.8,"znear":0.1}}],)"
                      R"("extensions":{"KHR_lights_punctual":{"lights":[{"type":"spot","intensity":2,"spot":{}}]}})");
  const fs::path path = test::write_file(dir, "camera.gltf", file);
  const Model model = read_model(path);
  ASSERT_EQ(model.camera_nodes, std::vector<std::int32_t>{1});
  ASSERT_EQ(model.light_nodes, std::vector<std::int32_t>{1});
  const Mesh posed = flatten(pose(model, 0, 0.5, path.string()), path.string());
  EXPECT_EQ(glm::vec3(posed.cameras[0].world_from_camera[3]), glm::vec3(1, 0, 5));
  EXPECT_EQ(posed.lights[0].vector, glm::vec3(1, 0, 5));
  EXPECT_EQ(posed.lights[0].spot_direction, glm::vec3(0, 0, -1));
  // Through the render job: the file's camera, seen at 0.75 s, is where its node is then.
  RenderJob job;
  job.model = path;
  job.width = 32;
  job.height = 24;
  job.camera.file_camera = 0;
  job.animation.time = 0.75;
  Renderer renderer(1);
  std::string camera;
  render_buffers(job, renderer, BufferRequest{}, &camera);
  const auto pose_of = nlohmann::json::parse(camera)["world_from_camera"];
  EXPECT_NEAR(pose_of[0][3].get<float>(), 1.5f, 1e-6f) << camera;
  EXPECT_NEAR(pose_of[2][3].get<float>(), 5.0f, 1e-6f) << camera;
}

TEST(GltfAnimation, BrokenSkinsAreRefusedNamingTheProblem) {
  const fs::path dir = test::scratch_dir("gltf_skins");
  std::string file = test::square_gltf(R"({"children":[0]},{"children":[0]})", 2, "");
  EXPECT_NE(test::load_problem(test::write_file(dir, "a.gltf", file)).find("node 0 has more than one parent"),
            std::string::npos);
  file = test::square_gltf(R"({"translation":[1,0,0]})", 1, R"(,"skins":[{"joints":[7]}])");
  EXPECT_NE(test::load_problem(test::write_file(dir, "b.gltf", file)).find("skin 0's joint node 7 does not exist"),
            std::string::npos);
  file = test::square_gltf(R"({"children":[2]},{"children":[1]})", 2, "");
  EXPECT_NE(test::load_problem(test::write_file(dir, "c.gltf", file)).find("is its own ancestor"), std::string::npos);
}

}  // namespace
}  // namespace facet::gltf_animation_tests

namespace facet::gltf_animation_tests {
namespace {

// A skinned square: its four corners weighted to joint 0 of skin 0 (node 1, moved up by 1) with the weights given,
// the last corner's joint index as given.
std::string skinned_square(const float (&weights)[16], std::uint8_t last_joint) {
  const float positions[] = {-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0};
  const std::uint32_t indices[] = {0, 1, 2, 0, 2, 3};
  const std::uint8_t joints[16] = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, last_joint, 0, 0, 0};
  std::string buffer;
  for (const auto& [data, size] : {std::pair<const void*, std::size_t>{positions, sizeof positions},
                                   {indices, sizeof indices},
                                   {joints, sizeof joints},
                                   {weights, sizeof weights}})
    buffer.append(static_cast<const char*>(data), size);
  return R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0,1]}],)"
         R"("nodes":[{"mesh":0,"skin":0},{"translation":[0,1,0]}],"skins":[{"joints":[1]}],)"
         R"("meshes":[{"primitives":[{"attributes":{"POSITION":0,"JOINTS_0":2,"WEIGHTS_0":3},"indices":1}]}],)"
         R"("accessors":[{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3","min":[-1,-1,0],"max":[1,1,0]},)"
         R"({"bufferView":1,"componentType":5125,"count":6,"type":"SCALAR"},)"
         R"({"bufferView":2,"componentType":5121,"count":4,"type":"VEC4"},)"
         R"({"bufferView":3,"componentType":5126,"count":4,"type":"VEC4"}],)"
         R"("bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":48},{"buffer":0,"byteOffset":48,"byteLength":24},)"
         R"({"buffer":0,"byteOffset":72,"byteLength":16},{"buffer":0,"byteOffset":88,"byteLength":64}],)"
         R"("buffers":[{"byteLength":152,"uri":"data:application/octet-stream;base64,)" +
         test::base64(buffer) + R"("}]})";
}

TEST(GltfAnimation, SkinWeightsAreMendedWithAWarningAndJointsPastTheSkinRefused) {
  const fs::path dir = test::scratch_dir("gltf_weights");
  // Corner 0 weighs 0.5, corner 1 -1 (taken as 0: it follows its node), corners 2 and 3 weigh 1.
  const float weights[16] = {0.5f, 0, 0, 0, -1, 0, 0, 0, 1, 0, 0, 0, 0.25f, 0.75f, 0, 0};
  const fs::path path = test::write_file(dir, "weights.gltf", skinned_square(weights, 0));
  WarningCapture capture;
  const Mesh mesh = load_model(path);
  std::string all;
  for (const std::string& w : capture.messages()) all += w + "\n";
  EXPECT_NE(all.find("mesh 0: 1 vertices have negative or non-finite skin weights, taken as 0"), std::string::npos)
      << all;
  EXPECT_NE(all.find("mesh 0: 1 vertices' skin weights do not sum to 1; they are normalised"), std::string::npos)
      << all;
  // Skinned by the joint (1 up), except corner 1, which follows its node (unmoved).
  EXPECT_EQ(mesh.positions[0], glm::vec3(-1, 0, 0));
  EXPECT_EQ(mesh.positions[1], glm::vec3(1, -1, 0));
  EXPECT_EQ(mesh.positions[2], glm::vec3(1, 2, 0));
  EXPECT_EQ(mesh.positions[3], glm::vec3(-1, 2, 0));
  // Corner 3 weighted to joint 5 of a skin of one joint: refused.
  const std::string problem = test::load_problem(test::write_file(dir, "joints.gltf", skinned_square(weights, 5)));
  EXPECT_NE(problem.find("vertex 3 is weighted to joint 5, but skin 0 has 1 joints"), std::string::npos) << problem;
}

}  // namespace
}  // namespace facet::gltf_animation_tests
