// test_obj_loader.cpp - unit tests for load_model(): OBJ + MTL written on the fly, real assimp test models, bad input.
#include <gtest/gtest.h>

#include <unistd.h>
#include <algorithm>
#include <atomic>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string>

#include "facet/error.hpp"
#include "facet/model_io.hpp"
#include "support/load_problem.hpp"

namespace facet::obj_loader_tests {
namespace {

namespace fs = std::filesystem;

const fs::path kAssimpObj = "/usr/share/assimp/models/OBJ";

bool starts_with(const std::string& s, const std::string& prefix) { return s.rfind(prefix, 0) == 0; }

// Each test gets a fresh folder under the system temp dir, removed afterwards.
class ObjLoader : public ::testing::Test {
 protected:
  void SetUp() override {
    static std::atomic<int> counter{0};
    dir_ =
        fs::temp_directory_path() / ("facet_obj_test_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  fs::path write(const std::string& name, const std::string& bytes) const {
    return test::write_file(dir_, name, bytes);
  }
  static std::string problem(const fs::path& p) { return test::load_problem(p); }
  fs::path dir_;
};

const char* const kCubeObj = R"(# unit cube as 6 quads with uvs and normals
mtllib cube.mtl
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
v 0 0 1
v 1 0 1
v 1 1 1
v 0 1 1
vt 0 0
vt 1 0
vt 1 1
vt 0 1
vn 0 0 -1
vn 0 0 1
vn 0 -1 0
vn 0 1 0
vn -1 0 0
vn 1 0 0
usemtl red
f 1/1/1 4/2/1 3/3/1 2/4/1
f 5/1/2 6/2/2 7/3/2 8/4/2
usemtl wood
f 1/1/3 2/2/3 6/3/3 5/4/3
f 4/1/4 8/2/4 7/3/4 3/4/4
usemtl nowhere
f 1/1/5 5/2/5 8/3/5 4/4/5
usemtl red
f 2/1/6 3/2/6 7/3/6 6/4/6
)";

const char* const kCubeMtl = R"(newmtl red
Kd 1 0 0
Ks 0.5 0.5 0.5
Ns 64
d 0.75

newmtl wood
Kd 0.6 0.4 0.2
map_Kd textures\wood.png
)";

TEST_F(ObjLoader, QuadsMaterialsAndTextures) {
  write("cube.mtl", kCubeMtl);
  write("textures/wood.png", "not really a png");
  const fs::path obj = write("cube.obj", kCubeObj);
  testing::internal::CaptureStderr();
  const Mesh m = load_model(obj);
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
  EXPECT_EQ(m.triangle_count(), 12u);
  EXPECT_EQ(m.vertex_count(), 24u);  // every (v, vt, vn) triple is distinct
  EXPECT_EQ(m.normals.size(), 24u);
  EXPECT_EQ(m.uvs.size(), 24u);
  EXPECT_TRUE(m.colors.empty());
  // Quad 1 4 3 2 -> (1 4 3), (1 3 2), corners in file order.
  EXPECT_EQ(m.positions[m.indices[0]], glm::vec3(0, 0, 0));
  EXPECT_EQ(m.positions[m.indices[1]], glm::vec3(0, 1, 0));
  EXPECT_EQ(m.positions[m.indices[2]], glm::vec3(1, 1, 0));
  EXPECT_EQ(m.indices[3], m.indices[0]);
  EXPECT_EQ(m.indices[4], m.indices[2]);
  EXPECT_EQ(m.positions[m.indices[5]], glm::vec3(1, 0, 0));
  EXPECT_EQ(m.uvs[m.indices[1]], glm::vec2(1, 0));
  EXPECT_EQ(m.normals[m.indices[0]], glm::vec3(0, 0, -1));
  // Outward winding everywhere: face normal agrees with the file's normal.
  for (std::size_t t = 0; t < m.triangle_count(); ++t) {
    const glm::vec3 a = m.positions[m.indices[3 * t]], b = m.positions[m.indices[3 * t + 1]],
                    c = m.positions[m.indices[3 * t + 2]];
    EXPECT_GT(glm::dot(glm::cross(b - a, c - a), m.normals[m.indices[3 * t]]), 0) << "triangle " << t;
  }

  ASSERT_EQ(m.materials.size(), 2u);
  EXPECT_EQ(m.materials[0].name, "red");
  EXPECT_EQ(m.materials[0].diffuse, glm::vec4(1, 0, 0, 0.75f));
  EXPECT_EQ(m.materials[0].specular, glm::vec3(0.5f));
  EXPECT_EQ(m.materials[0].shininess, 64.0f);
  EXPECT_EQ(m.materials[0].diffuse_texture, "");
  EXPECT_EQ(m.materials[1].name, "wood");
  EXPECT_EQ(fs::path(m.materials[1].diffuse_texture), (dir_ / "textures/wood.png").lexically_normal());
  EXPECT_EQ(m.face_materials, (std::vector<std::int32_t>{0, 0, 0, 0, 1, 1, 1, 1, -1, -1, 0, 0}));
}

// MTL's PBR extension (Pr, Pm, Pc, Pcr, Ps) onto the physically based material; out-of-range values clamped.
TEST_F(ObjLoader, MtlPbrExtensionIsRead) {
  write("cube.mtl", "newmtl red\nKd 1 0 0\nPr 0.3\nPm 0.8\nPc 0.7\nPcr 0.2\nPs 0.4\n"
                    "newmtl wood\nKd 0.6 0.4 0.2\nPc 2\nPs -1\n");
  const Mesh m = load_model(write("cube.obj", kCubeObj));
  ASSERT_EQ(m.materials.size(), 2u);
  const Material& red = m.materials[0];
  EXPECT_FLOAT_EQ(red.roughness, 0.3f);
  EXPECT_FLOAT_EQ(red.metallic, 0.8f);
  EXPECT_FLOAT_EQ(red.clearcoat, 0.7f);
  EXPECT_FLOAT_EQ(red.clearcoat_roughness, 0.2f);
  EXPECT_EQ(red.sheen_color, glm::vec3(0.4f));
  EXPECT_FLOAT_EQ(red.sheen_roughness, 0.3f);
  EXPECT_FLOAT_EQ(m.materials[1].clearcoat, 1.0f);
  EXPECT_EQ(m.materials[1].sheen_color, glm::vec3(0.0f));
}

TEST_F(ObjLoader, MissingMtlAndTextureAreWarnings) {
  const fs::path obj = write("cube.obj", kCubeObj);
  testing::internal::CaptureStderr();
  const Mesh no_mtl = load_model(obj);
  std::string err = testing::internal::GetCapturedStderr();
  EXPECT_TRUE(starts_with(err, "facet: warning: " + obj.string() + ": material library 'cube.mtl': not found")) << err;
  EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
  EXPECT_TRUE(no_mtl.materials.empty());
  EXPECT_TRUE(no_mtl.face_materials.empty());
  EXPECT_EQ(no_mtl.triangle_count(), 12u);

  write("cube.mtl", kCubeMtl);  // but no textures/wood.png
  testing::internal::CaptureStderr();
  const Mesh no_texture = load_model(obj);
  err = testing::internal::GetCapturedStderr();
  EXPECT_TRUE(starts_with(err, "facet: warning: " + obj.string() + ": texture 'textures\\wood.png' of material 'wood'"))
      << err;
  EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
  ASSERT_EQ(no_texture.materials.size(), 2u);
  EXPECT_EQ(no_texture.materials[1].diffuse_texture, "");
}

TEST_F(ObjLoader, SharedVerticesAreDeduplicatedAndPartialAttributesDropped) {
  // Positions only: the 8 corners are shared by all faces. Relative (negative) indices, a concave hexagon, a
  // 2-corner face, a line and a point, CRLF line endings.
  const std::string text =
      "v 0 0 0\r\nv 2 0 0\r\nv 2 1 0\r\nv 1 1 0\r\nv 1 2 0\r\nv 0 2 0\r\nvn 0 0 1\r\n"
      "f 2 3 4 5 6 1\r\n"  // L shape starting at (2,0): a fan would fold over the notch
      "f -6 -5 -4\r\n"     // = f 1 2 3
      "f 1 2\r\nl 1 2 3\r\np 4\r\n"
      "f 1//1 2//1 3//1\r\n";  // only this face has normals
  testing::internal::CaptureStderr();
  const Mesh m = load_model(write("l.obj", text));
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_NE(err.find("dropped 1 face(s) with fewer than 3 corners"), std::string::npos) << err;
  EXPECT_EQ(m.triangle_count(), 4u + 1u + 1u);
  EXPECT_EQ(m.vertex_count(), 6u + 3u);  // 1..6 without a normal, 1..3 again with normal 1
  EXPECT_TRUE(m.normals.empty());        // not every corner has one
  EXPECT_TRUE(m.uvs.empty());
  double area = 0;
  for (std::size_t t = 0; t < 4; ++t) {
    const glm::vec3 a = m.positions[m.indices[3 * t]], b = m.positions[m.indices[3 * t + 1]],
                    c = m.positions[m.indices[3 * t + 2]];
    const float z = glm::cross(b - a, c - a).z;
    EXPECT_GT(z, 0) << "triangle " << t;
    area += 0.5 * z;
  }
  EXPECT_NEAR(area, 3.0, 1e-6);
  EXPECT_EQ(m.positions[m.indices[12]], glm::vec3(0, 0, 0));  // the relative face
  EXPECT_EQ(m.positions[m.indices[14]], glm::vec3(2, 1, 0));
}

TEST_F(ObjLoader, VertexColoursOnlyWhenEveryVertexHasThem) {
  const Mesh all = load_model(write("c.obj", "v 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 0 1 0 0 0 1\nf 1 2 3\n"));
  ASSERT_EQ(all.colors.size(), 3u);
  EXPECT_EQ(all.colors[1], glm::vec4(0, 1, 0, 1));
  const Mesh some = load_model(write("d.obj", "v 0 0 0 1 0 0\nv 1 0 0\nv 0 1 0 0 0 1\nf 1 2 3\n"));
  EXPECT_TRUE(some.colors.empty());
}

// A file of vertices and no faces is a point cloud: every `v` a point, with its colour where every `v` has one;
// `p` and `l` statements do not change that.
TEST_F(ObjLoader, VerticesWithoutFacesArePoints) {
  const Mesh cloud = load_model(write("points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\np 1 2 3\nl 1 2\n"));
  EXPECT_EQ(cloud.triangle_count(), 0u);
  EXPECT_EQ(cloud.points, (std::vector<std::uint32_t>{0, 1, 2}));
  EXPECT_EQ(cloud.positions[1], glm::vec3(1, 0, 0));
  EXPECT_TRUE(cloud.colors.empty());
  const Mesh colored = load_model(write("noext", "v 0 0 0 1 0 0\nv 1 2 3 0 0.5 1\n"));
  ASSERT_EQ(colored.points.size(), 2u);
  ASSERT_EQ(colored.colors.size(), 2u);
  EXPECT_EQ(colored.colors[1], glm::vec4(0, 0.5f, 1, 1));
  // A mesh keeps its faces and has no points.
  EXPECT_TRUE(load_model(write("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")).points.empty());
}

TEST_F(ObjLoader, BadFilesThrowInputErrorNamingThePath) {
  EXPECT_EQ(problem(dir_ / "missing.obj"), "no such file");
  EXPECT_EQ(problem(write("empty.obj", "")), "file is empty");
  fs::create_directories(dir_ / "folder.obj");
  EXPECT_EQ(problem(dir_ / "folder.obj"), "not a regular file");
  // Without a known extension the content decides: these read as OBJ, which then has nothing to draw.
  EXPECT_EQ(problem(write("model.dat", "# nothing but a comment\n")), "nothing to draw (no faces and no vertices)");
  EXPECT_EQ(problem(write("noext", "vn 0 0 1\n")), "nothing to draw (no faces and no vertices)");

  std::string garbage;
  std::uint32_t x = 12345;
  for (int i = 0; i < 4096; ++i) {
    x = x * 1664525u + 1013904223u;
    garbage.push_back(static_cast<char>(x >> 24));
  }
  const std::string g = problem(write("garbage.obj", garbage));
  EXPECT_TRUE(g == "no triangles found" || g.starts_with("nothing to draw") || starts_with(g, "malformed ")) << g;
  EXPECT_EQ(problem(write("blank.obj", "\n\n  # nothing\n")), "nothing to draw (no faces and no vertices)");

  const std::string eight = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n";
  EXPECT_EQ(problem(write("range.obj", eight + "f 1 2 3\nf 1 2 99\n")),
            "a face references vertex 99 but the file has 8");
  EXPECT_EQ(problem(write("before.obj", eight + "f 1 2 -9\n")),
            "a face references vertex before the first (relative index) but the file has 8");
  EXPECT_EQ(problem(write("uv.obj", eight + "vt 0 0\nf 1/1 2/2 3/1\n")),
            "a face references texture coordinate 2 but the file has 1");
  EXPECT_EQ(problem(write("vn.obj", eight + "f 1//1 2//1 3//1\n")), "a face references normal 1 but the file has 0");
  EXPECT_EQ(problem(write("zero.obj", eight + "f 0 1 2\n")),
            "malformed 'f' element on line 9 (an index is 0 or not a number)");
  EXPECT_EQ(problem(write("word.obj", eight + "f 1 2 3\nl 1 x\n")),
            "malformed 'l' element on line 10 (an index is 0 or not a number)");
  EXPECT_EQ(problem(write("nan.obj", "v 0 0 0\nv nan 1 0\nv 0 1 0\nf 1 2 3\n")),
            "non-finite vertex position on line 2");
  EXPECT_EQ(problem(write("inf.obj", "v 0 0 0\nv 1 -INF 0\nv 0 1 0\nf 1 2 3\n")),
            "non-finite vertex position on line 2");
  EXPECT_EQ(problem(write("huge.obj", "v 0 0 0\nv 1 0 0\nv 0 1e999 0\nf 1 2 3\n")),
            "non-finite vertex position (vertex 3)");
  std::string long_face = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf";
  for (int i = 0; i < 300; ++i) {
    long_face += ' ';
    long_face += static_cast<char>('1' + i % 3);
  }
  EXPECT_EQ(problem(write("long.obj", long_face + "\n")), "a polygon has more than 255 corners (not supported)");
}

TEST_F(ObjLoader, WusonHas3732Triangles) {
  if (!fs::exists(kAssimpObj / "WusonOBJ.obj")) GTEST_SKIP() << "assimp-testmodels not installed";
  const Mesh m = load_model(kAssimpObj / "WusonOBJ.obj");
  EXPECT_EQ(m.triangle_count(), 3732u);
  EXPECT_EQ(m.normals.size(), m.vertex_count());
  EXPECT_EQ(m.uvs.size(), m.vertex_count());  // a single shared vt (BENCHMARK.md 8.3: the renderer replaces it)
  EXPECT_TRUE(m.materials.empty());
  EXPECT_LT(m.vertex_count(), 3u * 3732u);  // indexed, not one vertex per corner
  EXPECT_FALSE(bounds(m).empty());
}

TEST_F(ObjLoader, SpiderMaterialsAndTextures) {
  if (!fs::exists(kAssimpObj / "spider.obj")) GTEST_SKIP() << "assimp-testmodels not installed";
  const Mesh m = load_model(kAssimpObj / "spider.obj");
  EXPECT_EQ(m.triangle_count(), 1368u);
  ASSERT_EQ(m.materials.size(), 5u);
  const std::vector<std::string> names = {"Skin", "Brusttex", "HLeibTex", "BeinTex", "Augentex"};
  const std::vector<std::string> textures = {"wal67ar_small.jpg", "wal69ar_small.jpg", "SpiderTex.jpg", "drkwood2.jpg",
                                             "engineflare1.jpg"};
  for (std::size_t i = 0; i < 5; ++i) {
    EXPECT_EQ(m.materials[i].name, names[i]);
    EXPECT_EQ(fs::path(m.materials[i].diffuse_texture), kAssimpObj / textures[i]);
    EXPECT_TRUE(fs::exists(m.materials[i].diffuse_texture));
  }
  EXPECT_NEAR(m.materials[0].diffuse.r, 0.827451f, 1e-6f);
  ASSERT_EQ(m.face_materials.size(), m.triangle_count());
  std::set<std::int32_t> used(m.face_materials.begin(), m.face_materials.end());
  EXPECT_EQ(used, (std::set<std::int32_t>{0, 2, 3, 4}));  // Brusttex is defined but never used
}

TEST_F(ObjLoader, CubeWithVertexColorsAndBox) {
  if (!fs::exists(kAssimpObj / "box.obj")) GTEST_SKIP() << "assimp-testmodels not installed";
  const Mesh c = load_model(kAssimpObj / "cube_with_vertexcolors.obj");
  EXPECT_EQ(c.triangle_count(), 12u);
  ASSERT_EQ(c.colors.size(), c.vertex_count());
  const glm::vec4 first = c.colors[c.indices[0]];  // v 0 0 0 0.48627 0.43137 0.47059
  EXPECT_NEAR(glm::distance(first, glm::vec4(0.48627f, 0.43137f, 0.47059f, 1.0f)), 0.0f, 1e-6f);
  EXPECT_EQ(c.normals.size(), c.vertex_count());

  const Mesh b = load_model(kAssimpObj / "box.obj");
  EXPECT_EQ(b.vertex_count(), 8u);
  EXPECT_EQ(b.triangle_count(), 12u);
  EXPECT_TRUE(b.normals.empty());
  EXPECT_TRUE(b.materials.empty());  // "usemtl Default" without an mtllib
  std::map<std::array<std::uint32_t, 2>, int> uses;
  for (std::size_t i = 0; i < b.indices.size(); i += 3)
    for (int k = 0; k < 3; ++k) ++uses[{b.indices[i + k], b.indices[i + (k + 1) % 3]}];
  EXPECT_EQ(uses.size(), 36u);  // 18 undirected edges, each used once per direction: closed and consistent
  for (const auto& [e, n] : uses) EXPECT_EQ(n, 1);
  for (const auto& [e, n] : uses) EXPECT_TRUE(uses.count({e[1], e[0]}));
}

// Every model must load into a valid mesh or fail with InputError, never crash, hang or throw anything else.
void load_or_input_error(const fs::path& p, int& loaded, int& refused) {
  try {
    const Mesh m = load_model(p);
    EXPECT_NO_THROW(validate(m, p.string())) << p;
    EXPECT_GT(m.triangle_count() + m.point_count(), 0u) << p;
    ++loaded;
  } catch (const InputError& e) {
    EXPECT_TRUE(starts_with(e.what(), p.string() + ": ")) << e.what();
    ++refused;
  } catch (const std::exception& e) {
    ADD_FAILURE() << p << ": unexpected exception: " << e.what();
  } catch (...) {
    ADD_FAILURE() << p << ": unexpected non-standard exception";
  }
}

TEST_F(ObjLoader, EveryAssimpObjFileLoadsOrThrowsInputError) {
  if (!fs::is_directory(kAssimpObj)) GTEST_SKIP() << "assimp-testmodels not installed";
  int loaded = 0, refused = 0;
  testing::internal::CaptureStderr();  // missing-MTL warnings
  for (const auto& entry : fs::directory_iterator(kAssimpObj)) load_or_input_error(entry.path(), loaded, refused);
  testing::internal::GetCapturedStderr();
  EXPECT_GE(loaded, 15);  // WusonOBJ, spider, the boxes and cubes, ...
  EXPECT_GT(refused, 0);  // the .jpg and .mtl files at least
}

TEST_F(ObjLoader, EveryAssimpModelRenamedToObjLoadsOrThrowsInputError) {
  const fs::path models = kAssimpObj.parent_path();
  if (!fs::is_directory(models)) GTEST_SKIP() << "assimp-testmodels not installed";
  // Symlinks named *.obj make every binary and foreign-format file go through the OBJ reader.
  int n = 0, loaded = 0, refused = 0;
  for (const auto& entry : fs::recursive_directory_iterator(models))
    if (entry.is_regular_file()) fs::create_symlink(entry.path(), dir_ / (std::to_string(n++) + ".obj"));
  testing::internal::CaptureStderr();
  for (int i = 0; i < n; ++i) load_or_input_error(dir_ / (std::to_string(i) + ".obj"), loaded, refused);
  testing::internal::GetCapturedStderr();
  EXPECT_EQ(loaded + refused, n);
  EXPECT_GT(n, 100);
}

}  // namespace
}  // namespace facet::obj_loader_tests
