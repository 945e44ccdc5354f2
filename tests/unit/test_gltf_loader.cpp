// test_gltf_loader.cpp - glTF 2.0 through load_model(): the three forms of one file, node transforms, real files.
#include <gtest/gtest.h>
#include <meshoptimizer.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "facet/color.hpp"
#include "facet/error.hpp"
#include "facet/mesh.hpp"
#include "facet/model_io.hpp"
#include "facet/texture.hpp"
#include "facet/warnings.hpp"
#include "support/base64.hpp"
#include "support/load_problem.hpp"
#include "support/scratch_dir.hpp"

namespace facet::gltf_loader_tests {
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

// A POINTS primitive (mode 0) gives points, indexed or not, with its vertex colours; LINES are skipped with a
// warning.
TEST(GltfLoader, PointsPrimitivesArePointsAndLinesAreSkipped) {
  const float positions[] = {-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0};
  const std::uint32_t indices[] = {0, 2};
  std::string buffer(sizeof positions + sizeof indices, '\0');
  std::memcpy(buffer.data(), positions, sizeof positions);
  std::memcpy(buffer.data() + sizeof positions, indices, sizeof indices);
  const auto file = [&](const std::string& primitives) {
    return R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],)"
           R"("meshes":[{"primitives":[)" + primitives + R"(]}],)"
           R"("accessors":[{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3","min":[-1,-1,0],)"
           R"("max":[1,1,0]},{"bufferView":1,"componentType":5125,"count":2,"type":"SCALAR"}],)"
           R"("bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":48},{"buffer":0,"byteOffset":48,"byteLength":8}],)"
           R"("buffers":[{"byteLength":56,"uri":"data:application/octet-stream;base64,)" + test::base64(buffer) +
           R"("}]})";
  };
  const fs::path dir = test::scratch_dir("gltf_points");
  const auto write = [&](const std::string& name, const std::string& text) {
    return test::write_file(dir, name, text);
  };
  const Mesh all = load_model(write("all.gltf", file(R"({"attributes":{"POSITION":0},"mode":0})")));
  EXPECT_EQ(all.triangle_count(), 0u);
  EXPECT_EQ(all.points, (std::vector<std::uint32_t>{0, 1, 2, 3}));
  EXPECT_EQ(all.positions[2], glm::vec3(1, 1, 0));
  const Mesh two = load_model(write("two.gltf", file(R"({"attributes":{"POSITION":0},"indices":1,"mode":0})")));
  EXPECT_EQ(two.points, (std::vector<std::uint32_t>{0, 2}));
  testing::internal::CaptureStderr();
  EXPECT_EQ(test::load_problem(write("lines.gltf", file(R"({"attributes":{"POSITION":0},"indices":1,"mode":1})"))),
            "the default scene has no triangles and no points");
  EXPECT_NE(testing::internal::GetCapturedStderr().find("lines are not drawn"), std::string::npos);
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

// EXT_meshopt_compression: a small mesh compressed here with meshoptimizer's own encoders, in a .gltf (data: URI
// buffer) and a GLB (BIN chunk), each with the uncompressed views' placeholder buffer the extension marks as a
// fallback and gives no data, as gltfpack writes them.
struct MeshoptMesh {
  std::vector<glm::vec3> positions, normals;
  std::vector<std::uint32_t> indices;
};

// An 8 x 8 grid of vertices, 98 triangles: large enough that the uncompressed views (the placeholder buffer's
// byteLength) are larger than the compressed data (a GLB's BIN chunk).
MeshoptMesh meshopt_mesh() {
  MeshoptMesh m;
  constexpr std::uint32_t kSide = 8;
  for (std::uint32_t y = 0; y < kSide; ++y)
    for (std::uint32_t x = 0; x < kSide; ++x) {
      m.positions.emplace_back(0.25f * static_cast<float>(x), -0.5f * static_cast<float>(y),
                               0.125f * static_cast<float>(x * y % 5));
      const float a = 0.9f * static_cast<float>(x), b = 0.3f + 0.2f * static_cast<float>(y);
      m.normals.push_back(glm::normalize(glm::vec3(std::cos(a) * std::sin(b), std::sin(a) * std::sin(b), std::cos(b))));
    }
  for (std::uint32_t y = 0; y + 1 < kSide; ++y)
    for (std::uint32_t x = 0; x + 1 < kSide; ++x) {
      const std::uint32_t v = y * kSide + x;
      m.indices.insert(m.indices.end(), {v, v + kSide, v + 1, v + 1, v + kSide, v + kSide + 1});
    }
  return m;
}

template <class T>
std::string bytes_of(const std::vector<T>& values) {
  return std::string(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
}

std::string encoded_vertices(const std::string& raw, std::size_t stride) {
  const std::size_t count = raw.size() / stride;
  std::string out(meshopt_encodeVertexBufferBound(count, stride), '\0');
  out.resize(
      meshopt_encodeVertexBuffer(reinterpret_cast<unsigned char*>(out.data()), out.size(), raw.data(), count, stride));
  return out;
}

// How the test file stores its normals and indices.
struct MeshoptLayout {
  bool octahedral_normals = false;  // 16-bit octahedral (filter OCTAHEDRAL, stride 8) rather than floats
  bool index_sequence = false;      // 16-bit indices in INDICES mode rather than 32-bit ones in TRIANGLES mode
};

// The file's JSON (buffer 0, the compressed data, has no uri yet) and buffer 0's bytes.
struct MeshoptFile {
  nlohmann::json gltf;
  std::string data;
};

MeshoptFile meshopt_file(const MeshoptMesh& mesh, MeshoptLayout layout) {
  MeshoptFile file;
  nlohmann::json views = nlohmann::json::array();
  std::size_t fallback_bytes = 0;
  // One compressed view: its data appended to buffer 0, its uncompressed place in buffer 1, the fallback.
  const auto view = [&](const std::string& compressed, std::size_t stride, std::size_t count, const char* mode,
                        const char* filter, bool vertex_stride) {
    nlohmann::json extension = {{"buffer", 0},
                                {"byteOffset", file.data.size()},
                                {"byteLength", compressed.size()},
                                {"byteStride", stride},
                                {"count", count},
                                {"mode", mode}};
    if (filter) extension["filter"] = filter;
    nlohmann::json v = {{"buffer", 1},
                        {"byteOffset", fallback_bytes},
                        {"byteLength", count * stride},
                        {"extensions", {{"EXT_meshopt_compression", extension}}}};
    if (vertex_stride) v["byteStride"] = stride;
    views.push_back(v);
    fallback_bytes += (count * stride + 3) / 4 * 4;
    file.data += compressed;
    file.data.append((4 - file.data.size() % 4) % 4, '\0');
    return views.size() - 1;
  };
  const std::size_t n = mesh.positions.size();
  const std::size_t positions =
      view(encoded_vertices(bytes_of(mesh.positions), 12), 12, n, "ATTRIBUTES", nullptr, true);
  std::size_t normals;
  if (layout.octahedral_normals) {
    std::vector<float> xyzw;
    for (const glm::vec3& v : mesh.normals) xyzw.insert(xyzw.end(), {v.x, v.y, v.z, 0.0f});
    std::vector<std::int16_t> filtered(4 * n);
    meshopt_encodeFilterOct(filtered.data(), n, 8, 16, xyzw.data());
    normals = view(encoded_vertices(bytes_of(filtered), 8), 8, n, "ATTRIBUTES", "OCTAHEDRAL", true);
  } else {
    normals = view(encoded_vertices(bytes_of(mesh.normals), 12), 12, n, "ATTRIBUTES", nullptr, true);
  }
  const std::size_t count = mesh.indices.size();
  std::size_t indices;
  if (layout.index_sequence) {
    std::string out(meshopt_encodeIndexSequenceBound(count, n), '\0');
    out.resize(meshopt_encodeIndexSequence(reinterpret_cast<unsigned char*>(out.data()), out.size(),
                                           mesh.indices.data(), count));
    indices = view(out, 2, count, "INDICES", nullptr, false);
  } else {
    std::string out(meshopt_encodeIndexBufferBound(count, n), '\0');
    out.resize(meshopt_encodeIndexBuffer(reinterpret_cast<unsigned char*>(out.data()), out.size(), mesh.indices.data(),
                                         count));
    indices = view(out, 4, count, "TRIANGLES", nullptr, false);
  }

  glm::vec3 low = mesh.positions[0], high = mesh.positions[0];
  for (const glm::vec3& p : mesh.positions) low = glm::min(low, p), high = glm::max(high, p);
  nlohmann::json& g = file.gltf;
  g["asset"] = {{"version", "2.0"}};
  g["extensionsUsed"] = {"EXT_meshopt_compression"};
  g["extensionsRequired"] = {"EXT_meshopt_compression"};
  g["buffers"] = {
      {{"byteLength", file.data.size()}},
      {{"byteLength", fallback_bytes}, {"extensions", {{"EXT_meshopt_compression", {{"fallback", true}}}}}}};
  g["bufferViews"] = views;
  g["accessors"] = {{{"bufferView", positions},
                     {"componentType", 5126},
                     {"count", n},
                     {"type", "VEC3"},
                     {"min", {low.x, low.y, low.z}},
                     {"max", {high.x, high.y, high.z}}},
                    {{"bufferView", normals},
                     {"componentType", layout.octahedral_normals ? 5122 : 5126},
                     {"normalized", layout.octahedral_normals},
                     {"count", n},
                     {"type", "VEC3"}},
                    {{"bufferView", indices},
                     {"componentType", layout.index_sequence ? 5123 : 5125},
                     {"count", count},
                     {"type", "SCALAR"}}};
  g["meshes"] = {{{"primitives", {{{"attributes", {{"POSITION", 0}, {"NORMAL", 1}}}, {"indices", 2}}}}}};
  g["nodes"] = {{{"mesh", 0}}};
  g["scenes"] = {{{"nodes", {0}}}};
  g["scene"] = 0;
  return file;
}

std::string as_gltf(MeshoptFile file) {
  file.gltf["buffers"][0]["uri"] = "data:application/octet-stream;base64," + test::base64(file.data);
  return file.gltf.dump();
}

std::string as_glb(const MeshoptFile& file) {
  std::string json = file.gltf.dump();
  json.append((4 - json.size() % 4) % 4, ' ');
  const auto u32 = [](std::size_t v) {
    const auto x = static_cast<std::uint32_t>(v);
    return std::string(reinterpret_cast<const char*>(&x), 4);
  };
  return "glTF" + u32(2) + u32(12 + 8 + json.size() + 8 + file.data.size()) + u32(json.size()) + "JSON" + json +
         u32(file.data.size()) + std::string("BIN\0", 4) + file.data;
}

void expect_meshopt_mesh(const Mesh& got, const MeshoptMesh& want, float normal_tolerance) {
  EXPECT_EQ(got.positions, want.positions);
  EXPECT_EQ(got.indices, want.indices);
  ASSERT_EQ(got.normals.size(), want.normals.size());
  for (std::size_t i = 0; i < want.normals.size(); ++i)
    for (int axis = 0; axis < 3; ++axis)
      EXPECT_NEAR(got.normals[i][axis], want.normals[i][axis], normal_tolerance) << i;
}

TEST(GltfLoader, MeshoptCompressedViewsDecodeToTheOriginalMesh) {
  const fs::path dir = test::scratch_dir("gltf_meshopt");
  const MeshoptMesh mesh = meshopt_mesh();
  // Float normals and 32-bit TRIANGLES indices, in a .gltf: everything exact (facet renormalizes the normals).
  const MeshoptFile plain = meshopt_file(mesh, {});
  ASSERT_GT(plain.gltf["buffers"][1]["byteLength"].get<std::size_t>(), plain.data.size());
  expect_meshopt_mesh(load_model(test::write_file(dir, "plain.gltf", as_gltf(plain))), mesh, 1e-6f);
  // The same as a GLB, whose placeholder buffer made tinygltf fail ("Invalid `byteLength'").
  expect_meshopt_mesh(load_model(test::write_file(dir, "plain.glb", as_glb(plain))), mesh, 1e-6f);
  // 16-bit octahedral normals (OCTAHEDRAL filter) and 16-bit INDICES: normals within the filter's precision.
  const MeshoptFile packed = meshopt_file(mesh, {.octahedral_normals = true, .index_sequence = true});
  expect_meshopt_mesh(load_model(test::write_file(dir, "packed.glb", as_glb(packed))), mesh, 1e-3f);
  expect_meshopt_mesh(load_model(test::write_file(dir, "packed.gltf", as_gltf(packed))), mesh, 1e-3f);
  // A fallback buffer with a uri is not read: the file it names need not exist.
  MeshoptFile named = plain;
  named.gltf["buffers"][1]["uri"] = "missing.bin";
  expect_meshopt_mesh(load_model(test::write_file(dir, "named.gltf", as_gltf(named))), mesh, 1e-6f);
  // A compressed view no mesh reads is not decoded, however broken.
  MeshoptFile unread = plain;
  nlohmann::json extra = unread.gltf["bufferViews"][0];
  extra["extensions"]["EXT_meshopt_compression"]["mode"] = "SOMETHING";
  unread.gltf["bufferViews"].push_back(extra);
  expect_meshopt_mesh(load_model(test::write_file(dir, "unread.gltf", as_gltf(unread))), mesh, 1e-6f);
}

TEST(GltfLoader, BrokenMeshoptViewsAreRefusedNamingTheExtension) {
  const fs::path dir = test::scratch_dir("gltf_meshopt_broken");
  const MeshoptFile good = meshopt_file(meshopt_mesh(), {});
  const std::size_t positions_size = good.gltf["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["byteLength"];
  struct Case {
    const char* name;
    std::function<void(nlohmann::json&)> change;
    const char* problem;
  };
  const auto positions = [](nlohmann::json& g) -> nlohmann::json& {
    return g["bufferViews"][0]["extensions"]["EXT_meshopt_compression"];
  };
  const Case cases[] = {
      // The stream cut short: the decoder finds its tail missing.
      {"truncated", [&](nlohmann::json& g) { positions(g)["byteLength"] = positions_size - 8; },
       "bufferView 0: EXT_meshopt_compression: the"},
      // A count the buffer view does not hold, then one it does (the view's byteLength lying along) but the
      // stream does not, then one past what the stream could expand to. (A count within the stream's last group of
      // 16 elements decodes: the codec cannot tell it from the truth, and the accessor reads its own count.)
      {"count", [&](nlohmann::json& g) { positions(g)["count"] = 70; }, "but the buffer view's byteLength is 768"},
      {"count_and_length",
       [&](nlohmann::json& g) {
         positions(g)["count"] = 200;
         g["bufferViews"][0]["byteLength"] = 2400;
       },
       "not a valid ATTRIBUTES stream of 200 elements"},
      {"count_past_the_codec",
       [&](nlohmann::json& g) {
         positions(g)["count"] = 100000;
         g["bufferViews"][0]["byteLength"] = 1200000;
       },
       "more than 64 times its"},
      {"negative_count", [&](nlohmann::json& g) { positions(g)["count"] = -6; }, "count is not a non-negative integer"},
      {"huge_count", [&](nlohmann::json& g) { positions(g)["count"] = 3000000000u; }, "count is not a non-negative"},
      {"offset", [&](nlohmann::json& g) { positions(g)["byteOffset"] = 1000000; }, "reach past the end of buffer 0"},
      {"buffer", [&](nlohmann::json& g) { positions(g)["buffer"] = 7; }, "buffer 7 does not exist"},
      {"fallback_source", [&](nlohmann::json& g) { positions(g)["buffer"] = 1; }, "buffer 1 is a placeholder"},
      {"stride", [&](nlohmann::json& g) { positions(g)["byteStride"] = 6; }, "byteStride 6 is not a multiple of 4"},
      {"view_stride", [&](nlohmann::json& g) { g["bufferViews"][0]["byteStride"] = 16; }, "differs from"},
      {"mode", [&](nlohmann::json& g) { positions(g)["mode"] = "POINTS"; }, "mode 'POINTS' is not ATTRIBUTES"},
      {"no_mode", [&](nlohmann::json& g) { positions(g).erase("mode"); }, "it has no mode"},
      {"filter", [&](nlohmann::json& g) { positions(g)["filter"] = "QUATERNION"; }, "byteStride 12 is not 8"},
      {"index_stride",
       [&](nlohmann::json& g) { g["bufferViews"][2]["extensions"]["EXT_meshopt_compression"]["byteStride"] = 1; },
       "bufferView 2: EXT_meshopt_compression: byteStride 1 is not 2 or 4"},
      {"index_count",
       [&](nlohmann::json& g) { g["bufferViews"][2]["extensions"]["EXT_meshopt_compression"]["count"] = 11; },
       "count 11 is not a multiple of 3"},
  };
  for (const Case& c : cases) {
    MeshoptFile file = good;
    c.change(file.gltf);
    const std::string problem = test::load_problem(test::write_file(dir, std::string(c.name) + ".gltf", as_gltf(file)));
    EXPECT_NE(problem.find("EXT_meshopt_compression"), std::string::npos) << c.name << ": " << problem;
    EXPECT_NE(problem.find(c.problem), std::string::npos) << c.name << ": " << problem;
  }
  // The same file also requiring an extension facet does not know is refused naming that one.
  MeshoptFile unknown = good;
  unknown.gltf["extensionsUsed"].push_back("EXT_unknown_codec");
  unknown.gltf["extensionsRequired"].push_back("EXT_unknown_codec");
  expect_input_error(test::write_file(dir, "unknown.gltf", as_gltf(unknown)), "EXT_unknown_codec");
}

// KHR_texture_basisu (KTX2) and EXT_texture_webp (WebP) images are not decoded: a texture with no PNG or JPEG
// source beside them leaves its material untextured with one warning naming the extension; one with such a source
// uses it, without a word.
TEST(GltfLoader, TexturesFacetCannotDecodeAreNamedInAWarning) {
  const fs::path dir = test::scratch_dir("gltf_texture_extensions");
  test::write_file(dir, "a.ktx2", std::string("\xABKTX 20\xBB\r\n\x1A\n", 12) + std::string(64, '\0'));
  test::write_file(dir, "b.webp", std::string("RIFF\x20\0\0\0WEBPVP8 ", 16) + std::string(32, '\0'));
  fs::copy_file(kGltf / "BoxTextured-glTF/CesiumLogoFlat.png", dir / "c.png", fs::copy_options::overwrite_existing);
  nlohmann::json g = nlohmann::json::parse(
      R"({"asset":{"version":"2.0"},"extensionsUsed":["KHR_texture_basisu","EXT_texture_webp"],"buffers":[{"byteLength":36,"uri":"data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}],"bufferViews":[{"buffer":0,"byteLength":36}],"accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]}],"nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}],"scene":0})");
  g["images"] = {{{"uri", "a.ktx2"}}, {{"uri", "b.webp"}}, {{"uri", "c.png"}}};
  g["textures"] = {{{"extensions", {{"KHR_texture_basisu", {{"source", 0}}}}}},
                   {{"extensions", {{"EXT_texture_webp", {{"source", 1}}}}}},
                   {{"source", 2}, {"extensions", {{"KHR_texture_basisu", {{"source", 0}}}}}}};
  // Materials 0 and 3 share texture 0: one warning for it.
  g["materials"] = nlohmann::json::array();
  for (int texture : {0, 1, 2, 0})
    g["materials"].push_back({{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", texture}}}}}});
  nlohmann::json primitives = nlohmann::json::array();
  for (int material = 0; material < 4; ++material)
    primitives.push_back({{"attributes", {{"POSITION", 0}}}, {"material", material}});
  g["meshes"] = {{{"primitives", primitives}}};
  WarningCapture warnings;
  const Mesh mesh = load_model(test::write_file(dir, "textures.gltf", g.dump()));
  ASSERT_EQ(mesh.materials.size(), 4u);
  EXPECT_FALSE(mesh.materials[0].diffuse_map);
  EXPECT_FALSE(mesh.materials[1].diffuse_map);
  EXPECT_TRUE(mesh.materials[2].diffuse_map);
  EXPECT_FALSE(mesh.materials[3].diffuse_map);
  ASSERT_EQ(warnings.messages().size(), 2u) << ::testing::PrintToString(warnings.messages());
  EXPECT_NE(warnings.messages()[0].find("texture 0 has only a KTX2 image (KHR_texture_basisu)"), std::string::npos)
      << warnings.messages()[0];
  EXPECT_NE(warnings.messages()[1].find("texture 1 has only a WebP image (EXT_texture_webp)"), std::string::npos)
      << warnings.messages()[1];
  for (const std::string& message : warnings.messages()) {
    EXPECT_NE(message.find("untextured"), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

// Every glTF file Debian ships either loads (at least one triangle or point, validated) or is refused with
// InputError.
TEST(GltfLoader, EveryAssimpModelLoadsOrThrowsInputError) {
  int loaded = 0, refused = 0;
  for (const auto& entry : fs::recursive_directory_iterator(kGltf)) {
    const std::string ext = entry.path().extension().string();
    if (ext != ".gltf" && ext != ".glb") continue;
    try {
      const Mesh m = load_model(entry.path());
      EXPECT_GT(m.triangle_count() + m.point_count(), 0u) << entry.path();
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
}  // namespace facet::gltf_loader_tests

namespace facet::gltf_loader_tests {
namespace {

// An image whose buffer view reaches past its buffer is refused naming both, before any of its bytes are read
// (tinygltf hands the image loader such a view unchecked).
TEST(GltfLoader, ImageBufferViewPastItsBufferIsRefused) {
  const std::filesystem::path dir = test::scratch_dir("gltf_image_view");
  const std::filesystem::path model = test::write_file(
      dir, "image_view.gltf",
      R"({"asset":{"version":"2.0"},"buffers":[{"byteLength":36,)"
      R"("uri":"data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}],)"
      R"("bufferViews":[{"buffer":0,"byteLength":36},{"buffer":0,"byteOffset":100000000,"byteLength":100}],)"
      R"("accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]}],)"
      R"("images":[{"bufferView":1,"mimeType":"image/png"}],"textures":[{"source":0}],)"
      R"("meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],"nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}],)"
      R"("scene":0})");
  EXPECT_EQ(test::load_problem(model), "image 0: buffer view 1 reaches past the end of its buffer");
}

}  // namespace
}  // namespace facet::gltf_loader_tests
