// test_ply_loader.cpp - unit tests for load_model() on PLY: all three encodings written on the fly, bad input, models.
#include <gtest/gtest.h>

#include <bit>
#include <charconv>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "facet/error.hpp"
#include "facet/model_io.hpp"
#include "support/load_problem.hpp"
#include "support/scratch_dir.hpp"

namespace facet::ply_loader_tests {
namespace {

namespace fs = std::filesystem;

const fs::path kAssimpPly = "/usr/share/assimp/models/PLY";
const char* const kEncodings[] = {"ascii", "binary_little_endian", "binary_big_endian"};

// A PLY file built from typed values, so that one description gives the same data in every encoding.
class PlyWriter {
 public:
  explicit PlyWriter(std::string encoding) : encoding_(std::move(encoding)) {}

  PlyWriter& header(const std::string& line) {
    header_ += line + "\n";
    return *this;
  }

  // Appends one value of the named PLY type to the body.
  PlyWriter& put(const std::string& type, double v) {
    const std::map<std::string, int> sizes = {{"char", 1},  {"uchar", 1},  {"short", 2}, {"ushort", 2},
                                              {"int", 4},   {"uint", 4},   {"int8", 1},  {"uint8", 1},
                                              {"int16", 2}, {"uint16", 2}, {"int32", 4}, {"uint32", 4}};
    const bool is_float = type == "float" || type == "float32", is_double = type == "double" || type == "float64";
    if (encoding_ == "ascii") {
      char text[64];
      char* end = is_float    ? std::to_chars(text, text + 64, static_cast<float>(v)).ptr
                  : is_double ? std::to_chars(text, text + 64, v).ptr
                              : std::to_chars(text, text + 64, static_cast<long long>(v)).ptr;
      body_ += std::string(text, end) + " ";
      return *this;
    }
    std::uint64_t bits = 0;
    int size = 0;
    if (is_float) {
      bits = std::bit_cast<std::uint32_t>(static_cast<float>(v));
      size = 4;
    } else if (is_double) {
      bits = std::bit_cast<std::uint64_t>(v);
      size = 8;
    } else {
      bits = static_cast<std::uint64_t>(static_cast<long long>(v));
      size = sizes.at(type);
    }
    for (int i = 0; i < size; ++i) {
      const int shift = encoding_ == "binary_little_endian" ? 8 * i : 8 * (size - 1 - i);
      body_.push_back(static_cast<char>(bits >> shift));
    }
    return *this;
  }

  PlyWriter& list(const std::string& count_type, const std::string& type, const std::vector<double>& values) {
    put(count_type, static_cast<double>(values.size()));
    for (const double v : values) put(type, v);
    return *this;
  }

  PlyWriter& row() {
    if (encoding_ == "ascii" && !body_.empty()) body_.back() = '\n';
    return *this;
  }

  std::string str() const { return "ply\nformat " + encoding_ + " 1.0\n" + header_ + "end_header\n" + body_; }
  std::size_t header_size() const { return str().size() - body_.size(); }

 private:
  std::string encoding_, header_, body_;
};

const glm::vec3 kPyramid[5] = {{-1, 0, -1}, {1, 0, -1}, {1, 0, 1}, {-1, 0, 1}, {0, 2, 0}};
const std::vector<std::vector<double>> kPyramidFaces = {{0, 1, 2, 3}, {3, 2, 4}, {2, 1, 4}, {1, 0, 4}, {0, 3, 4}};
const std::vector<std::uint32_t> kPyramidIndices = {0, 1, 2, 0, 2, 3, 3, 2, 4, 2, 1, 4, 1, 0, 4, 0, 3, 4};

// The pyramid with every vertex attribute, among unknown elements and unknown scalar and list properties.
std::string pyramid(const std::string& encoding, bool faces_first = false) {
  PlyWriter w(encoding);
  w.header("comment written by test_ply_loader").header("obj_info nothing to see");
  w.header("element material 2").header("property uchar ambient_red").header("property list uchar float coefficients");
  auto vertex_header = [&] {
    w.header("element vertex 5").header("property float x").header("property float32 y").header("property float z");
    w.header("property list uchar int neighbours").header("property float nx").header("property float ny");
    w.header("property float nz").header("property uchar red").header("property uint8 green");
    w.header("property uchar blue").header("property uchar alpha").header("property double quality");
    w.header("property float s").header("property float t");
  };
  auto face_header = [&] {
    w.header("element face 5").header("property uchar flags").header("property list uchar int vertex_indices");
    w.header("property list uchar float texcoord");
  };
  auto vertices = [&] {
    for (int i = 0; i < 5; ++i) {
      const glm::vec3 p = kPyramid[i];
      w.put("float", p.x).put("float32", p.y).put("float", p.z).list("uchar", "int", {1, 2, 3});
      w.put("float", 0.5 * i).put("float", -0.25 * i).put("float", 1);
      w.put("uchar", 50 * i).put("uint8", 255 - 50 * i).put("uchar", 7).put("uchar", 255);
      w.put("double", 1e300).put("float", 0.25 * i).put("float", 1 - 0.125 * i).row();
    }
  };
  auto faces = [&] {
    for (const std::vector<double>& f : kPyramidFaces)
      w.put("uchar", 9).list("uchar", "int", f).list("uchar", "float", {0.5, 1.5}).row();
  };
  if (faces_first) face_header();
  vertex_header();
  if (!faces_first) face_header();
  w.header("element edge 2").header("property int vertex1").header("property int vertex2");
  w.header("property list short ushort extra");
  w.put("uchar", 1).list("uchar", "float", {0.25, 0.5, 0.75}).row().put("uchar", 2).list("uchar", "float", {}).row();
  if (faces_first) faces();
  vertices();
  if (!faces_first) faces();
  w.put("int", 0).put("int", 1).list("short", "ushort", {7, 8}).row().put("int", 4).put("int", 2);
  w.list("short", "ushort", {}).row();
  return w.str();
}

class PlyLoader : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = test::scratch_dir("models"); }
  fs::path write(const std::string& name, const std::string& bytes) const {
    return test::write_file(dir_, name, bytes);
  }
  static std::string problem(const fs::path& p) { return test::load_problem(p); }
  fs::path dir_;
};

TEST_F(PlyLoader, EveryEncodingGivesTheSameMeshWithUnknownDataSkipped) {
  for (const bool faces_first : {false, true}) {
    for (const char* encoding : kEncodings) {
      SCOPED_TRACE(std::string(encoding) + (faces_first ? ", faces before vertices" : ""));
      const Mesh m = load_model(write("pyramid.ply", pyramid(encoding, faces_first)));
      EXPECT_EQ(m.positions, std::vector<glm::vec3>(std::begin(kPyramid), std::end(kPyramid)));
      EXPECT_EQ(m.indices, kPyramidIndices);  // the quad split as (c0 c1 c2), (c0 c2 c3), the rest in file order
      ASSERT_EQ(m.normals.size(), 5u);
      ASSERT_EQ(m.colors.size(), 5u);
      ASSERT_EQ(m.uvs.size(), 5u);
      for (int i = 0; i < 5; ++i) {
        EXPECT_EQ(m.normals[i], glm::vec3(0.5f * i, -0.25f * i, 1));
        const auto byte = [](double b) { return static_cast<float>(b / 255); };  // uchar / 255
        EXPECT_EQ(m.colors[i], glm::vec4(byte(50 * i), byte(255 - 50 * i), byte(7), 1));
        EXPECT_EQ(m.uvs[i], glm::vec2(0.25f * i, 1 - 0.125f * i));
      }
      EXPECT_TRUE(m.face_colors.empty());
      EXPECT_TRUE(m.materials.empty());
    }
  }
}

TEST_F(PlyLoader, FloatColoursAreKeptAsTheyAreAndAlphaDefaultsToOne) {
  for (const char* encoding : kEncodings) {
    SCOPED_TRACE(encoding);
    PlyWriter w(encoding);
    w.header("element vertex 3").header("property float x").header("property float y").header("property float z");
    w.header("property double diffuse_red").header("property float diffuse_green").header("property float blue");
    w.header("element face 1").header("property list uchar uint vertex_index");
    for (int i = 0; i < 3; ++i) {
      w.put("float", i == 1).put("float", i == 2).put("float", 0);
      w.put("double", 0.25).put("float", 0.5 * i).put("float", 2).row();
    }
    w.list("uchar", "uint", {0, 1, 2}).row();
    const Mesh m = load_model(write("colours.ply", w.str()));
    ASSERT_EQ(m.colors.size(), 3u);
    EXPECT_EQ(m.colors[2], glm::vec4(0.25f, 1.0f, 2.0f, 1.0f));
  }
}

TEST_F(PlyLoader, EveryTextureCoordinateNaming) {
  const char* const names[][2] = {{"s", "t"}, {"u", "v"}, {"texture_u", "texture_v"}, {"texture_s", "texture_t"}};
  for (const auto& uv : names) {
    SCOPED_TRACE(uv[0]);
    PlyWriter w("ascii");
    w.header("element vertex 3").header("property float x").header("property float y").header("property float z");
    w.header(std::string("property float ") + uv[0]).header(std::string("property float ") + uv[1]);
    w.header("element face 1").header("property list uchar int vertex_indices");
    for (int i = 0; i < 3; ++i)
      w.put("float", i == 1).put("float", i == 2).put("float", 0).put("float", i).put("float", -i);
    w.list("uchar", "int", {0, 1, 2});
    const Mesh m = load_model(write("uv.ply", w.str()));
    ASSERT_EQ(m.uvs.size(), 3u);
    EXPECT_EQ(m.uvs[2], glm::vec2(2, -2));
  }
}

TEST_F(PlyLoader, QuadsAndConcavePolygonsAreTriangulatedKeepingTheirWinding) {
  // An arrow head, concave at corner 3, and a quad; both counter-clockwise seen from +z.
  const std::vector<glm::vec3> corners = {{0, 0, 0}, {4, 0, 0}, {4, 4, 0}, {2, 1, 0}, {0, 4, 0},
                                          {5, 0, 0}, {6, 0, 0}, {6, 1, 0}, {5, 1, 0}};
  for (const char* encoding : kEncodings) {
    SCOPED_TRACE(encoding);
    PlyWriter w(encoding);
    w.header("element vertex 9").header("property float x").header("property float y").header("property float z");
    w.header("element face 2").header("property list int short vertex_indices");
    for (const glm::vec3& p : corners) w.put("float", p.x).put("float", p.y).put("float", p.z).row();
    w.list("int", "short", {0, 1, 2, 3, 4}).row().list("int", "short", {5, 6, 7, 8}).row();
    const Mesh m = load_model(write("polygons.ply", w.str()));
    std::vector<std::uint32_t> expected;
    const std::vector<std::uint32_t> arrow = {0, 1, 2, 3, 4};
    triangulate_polygon(corners, arrow, expected);
    expected.insert(expected.end(), {5, 6, 7, 5, 7, 8});
    EXPECT_EQ(m.indices, expected);
    ASSERT_EQ(m.triangle_count(), 5u);
    for (std::size_t t = 0; t < 5; ++t) {
      const glm::vec3 a = m.positions[m.indices[3 * t]], b = m.positions[m.indices[3 * t + 1]],
                      c = m.positions[m.indices[3 * t + 2]];
      EXPECT_GT(glm::cross(b - a, c - a).z, 0.0f) << "triangle " << t;
    }
  }
}

TEST_F(PlyLoader, ChosenByContentWhenTheExtensionSaysNothing) {
  EXPECT_EQ(load_model(write("no_extension", pyramid("binary_big_endian"))).triangle_count(), 6u);
  std::string crlf = pyramid("ascii");
  crlf.replace(0, 4, "ply\r\n");
  EXPECT_EQ(load_model(write("crlf.model", crlf)).triangle_count(), 6u);
  EXPECT_EQ(load_model(write("UPPER.PLY", pyramid("ascii"))).triangle_count(), 6u);
  EXPECT_EQ(
      load_model(write("model.txt", "# an OBJ by another name\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")).triangle_count(),
      1u);
  const std::string supported =
      "supported: .obj, .ply, .stl, .gltf, .glb, .xyz, .pts, .pcd, .splat and the formats Assimp reads)";
  EXPECT_EQ(problem(write("model.dat", "hello\n")), "unsupported model format '.dat' (" + supported);
  EXPECT_EQ(problem(write("noext", "hello\n")), "unsupported model format (no file extension; " + supported);
}

// A PLY without faces (no face element, or one of no entries) is a point cloud: every vertex a point, with its
// colour and normal. One of no vertices has nothing to draw.
TEST_F(PlyLoader, PointCloudsLoadAsPointsAndEmptyMeshesAreRefused) {
  PlyWriter w("binary_little_endian");
  w.header("element vertex 2").header("property float x").header("property float y").header("property float z");
  w.header("property uchar red").header("property uchar green").header("property uchar blue");
  for (int i = 0; i < 2; ++i) {
    w.put("float", 3 * i).put("float", 3 * i + 1).put("float", 3 * i + 2);
    w.put("uchar", 255 * i).put("uchar", 0).put("uchar", 255);
  }
  for (const char* name : {"cloud.ply", "cloud0.ply"}) {
    const Mesh cloud = load_model(write(name, w.str()));
    EXPECT_EQ(cloud.triangle_count(), 0u) << name;
    EXPECT_EQ(cloud.points, (std::vector<std::uint32_t>{0, 1})) << name;
    EXPECT_EQ(cloud.positions[1], glm::vec3(3, 4, 5)) << name;
    ASSERT_EQ(cloud.colors.size(), 2u) << name;
    EXPECT_EQ(cloud.colors[1], glm::vec4(1, 0, 1, 1)) << name;
    w.header("element face 0").header("property list uchar int vertex_indices");
  }
  // A scan's intensity, under the names scanners and CloudCompare write, as the file gives it.
  for (const char* name : {"intensity", "scalar_Intensity"}) {
    const Mesh scan = load_model(write("scan.ply", std::string("ply\nformat ascii 1.0\nelement vertex 2\n"
                                                               "property float x\nproperty float y\n"
                                                               "property float z\nproperty ushort ") +
                                                       name + "\nend_header\n0 0 0 1000\n1 1 1 65535\n"));
    EXPECT_EQ(scan.intensities, (std::vector<float>{1000, 65535})) << name;
  }
  EXPECT_EQ(problem(write("nothing.ply",
                          "ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\n"
                          "property float y\nproperty float z\nend_header\n")),
            "nothing to draw (no vertices and no faces)");
  EXPECT_EQ(problem(write("strips.ply",
                          "ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\n"
                          "element tristrips 0\nproperty list int int vertex_indices\nend_header\n")),
            "PLY triangle strips ('tristrips') are not supported");
}

TEST_F(PlyLoader, FacesWithFewerThanThreeCornersAreDroppedWithOneWarning) {
  PlyWriter w("ascii");
  w.header("element vertex 3").header("property float x").header("property float y").header("property float z");
  w.header("element face 4").header("property list uchar int vertex_indices");
  for (int i = 0; i < 3; ++i) w.put("float", i == 1).put("float", i == 2).put("float", 0).row();
  w.list("uchar", "int", {0, 1}).row().list("uchar", "int", {0, 1, 2}).row().list("uchar", "int", {}).row();
  w.list("uchar", "int", {2}).row();
  const fs::path p = write("dropped.ply", w.str());
  testing::internal::CaptureStderr();
  const Mesh m = load_model(p);
  EXPECT_EQ(testing::internal::GetCapturedStderr(),
            "facet: warning: " + p.string() + ": dropped 3 face(s) with fewer than 3 corners\n");
  EXPECT_EQ(m.indices, (std::vector<std::uint32_t>{0, 1, 2}));

  PlyWriter none("binary_big_endian");
  none.header("element vertex 3").header("property float x").header("property float y").header("property float z");
  none.header("element face 1").header("property list uchar int vertex_indices");
  for (int i = 0; i < 9; ++i) none.put("float", i);
  none.list("uchar", "int", {0, 1});
  testing::internal::CaptureStderr();
  EXPECT_EQ(problem(write("none.ply", none.str())), "no triangles found");
  testing::internal::GetCapturedStderr();
}

TEST_F(PlyLoader, UnknownHeaderLinesAndTrailingDataAreWarnings) {
  std::string text = pyramid("ascii");
  text.insert(text.find("element"), "Created by an old exporter\n");
  const fs::path p = write("credit.ply", text + "42\n");
  testing::internal::CaptureStderr();
  EXPECT_EQ(load_model(p).triangle_count(), 6u);
  const std::string warnings = testing::internal::GetCapturedStderr();
  EXPECT_NE(
      warnings.find(p.string() + ": skipped 1 unknown PLY header line(s), the first on line 5: 'Created by an old "
                                 "exporter'\n"),
      std::string::npos)
      << warnings;
  EXPECT_NE(warnings.find(p.string() + ": ignored text after the last element, from line"), std::string::npos)
      << warnings;
  testing::internal::CaptureStderr();
  EXPECT_EQ(load_model(write("tail.ply", pyramid("binary_little_endian") + "xyz")).triangle_count(), 6u);
  EXPECT_NE(testing::internal::GetCapturedStderr().find(": ignored 3 bytes after the last element"), std::string::npos);
}

TEST_F(PlyLoader, BadHeadersThrowInputErrorNamingTheLine) {
  const std::string start = "ply\nformat ascii 1.0\n";
  const std::string xyz = "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n";
  const std::string faces = "element face 1\nproperty list uchar int vertex_indices\n";
  EXPECT_EQ(problem(write("magic.ply", "plx\n" + xyz)), "not a PLY file (the first line is not 'ply')");
  EXPECT_EQ(problem(write("open.ply", start + xyz)), "the PLY header has no 'end_header' line (truncated?)");
  EXPECT_EQ(problem(write("format.ply", "ply\n" + xyz + "end_header\n")), "the PLY header has no 'format' line");
  EXPECT_EQ(problem(write("middle.ply", "ply\nformat binary_middle_endian 1.0\nend_header\n")),
            "PLY header line 2: unknown encoding 'binary_middle_endian' (ascii, binary_little_endian or "
            "binary_big_endian)");
  EXPECT_EQ(problem(write("version.ply", "ply\nformat ascii 2.0\nend_header\n")),
            "PLY header line 2: unsupported PLY version '2.0' (only 1.0)");
  EXPECT_EQ(problem(write("orphan.ply", start + "property float x\nend_header\n")),
            "PLY header line 3: a property before any element");
  EXPECT_EQ(problem(write("type.ply", start + "element vertex 1\nproperty float128 x\nend_header\n")),
            "PLY header line 4: unknown property type 'float128'");
  EXPECT_EQ(problem(write("count.ply", start + "element vertex -5\nend_header\n")),
            "PLY header line 3: element count '-5' is not a non-negative integer");
  EXPECT_EQ(problem(write("twice.ply", start + xyz + "property float x\nend_header\n")),
            "PLY header line 7: element 'vertex' has a second property named 'x'");
  EXPECT_EQ(problem(write("float_count.ply", start + xyz + "element face 1\nproperty list float int vertex_indices\n")),
            "PLY header line 8: list count type 'float' is not an integer type");
  EXPECT_EQ(problem(write("float_index.ply",
                          start + xyz + "element face 1\nproperty list uchar float vertex_indices\nend_header\n")),
            "PLY face property 'vertex_indices' has entries of type float (vertex indices must be integers)");
  EXPECT_EQ(problem(write("no_z.ply",
                          start + "element vertex 1\nproperty float x\nproperty float y\n" + faces + "end_header\n")),
            "PLY vertex element has no 'z' property");
  EXPECT_EQ(problem(write("no_list.ply", start + xyz + "element face 1\nproperty int vertex_indices\nend_header\n")),
            "PLY face property 'vertex_indices' is not a list");
  EXPECT_EQ(problem(write("no_indices.ply", start + xyz +
                                                "element face 1\nproperty list uchar int corners\n"
                                                "end_header\n")),
            "PLY face element has no 'vertex_indices' list");
  EXPECT_EQ(problem(write("no_vertex.ply", start + faces + "end_header\n")), "PLY file has no 'vertex' element");
}

TEST_F(PlyLoader, CountsBeyondTheFileAreRefusedBeforeAllocating) {
  for (const char* encoding : kEncodings) {
    SCOPED_TRACE(encoding);
    PlyWriter w(encoding);
    w.header("element vertex 2147483648").header("property float x").header("property float y");
    w.header("property float z").header("element face 1").header("property list uchar int vertex_indices");
    for (int i = 0; i < 250; ++i) w.put("float", i);
    const std::string text = w.str();
    const std::size_t body = text.size() - w.header_size();
    const std::string least = std::string(encoding) == "ascii" ? "6" : "12";
    EXPECT_EQ(problem(write("huge.ply", text)), "PLY element 'vertex' claims 2147483648 entries of at least " + least +
                                                    " bytes each, but only " + std::to_string(body) +
                                                    " bytes follow the header (truncated?)");
  }
}

// A triangle "0 1 2" over three vertices, with the face written by `face` (the list property's types as named).
std::string one_face(const std::string& encoding, const std::string& list_types,
                     const std::function<void(PlyWriter&)>& face, std::size_t* face_offset = nullptr) {
  PlyWriter w(encoding);
  w.header("element vertex 3").header("property float x").header("property float y").header("property uchar z");
  w.header("element face 1").header("property list " + list_types + " vertex_indices");
  for (int i = 0; i < 3; ++i) w.put("float", i == 1).put("float", i == 2).put("uchar", 0).row();
  if (face_offset) *face_offset = w.header_size() + 27;
  face(w);
  return w.str();
}

TEST_F(PlyLoader, BadBodiesThrowInputErrorNamingTheEntryAndWhere) {
  auto ascii = [&](const std::string& name, const std::string& body) {
    return problem(write(name,
                         "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                         "property uchar z\nelement face 1\nproperty list char int vertex_indices\nend_header\n" +
                             body));
  };
  const std::string vertices = "0 0 0\n1 0 0\n0 1 0\n";
  EXPECT_EQ(ascii("word.ply", "0 0 0\n1 abc 0\n0 1 0\n3 0 1 2\n"), "vertex 1: 'abc' is not a number (line 11)");
  EXPECT_EQ(ascii("uchar.ply", "0 0 300\n1 0 0\n0 1 0\n3 0 1 2\n"),
            "vertex 0: 300 does not fit its type, uchar (line 10)");
  EXPECT_EQ(ascii("fraction.ply", "0 0 0.5\n1 0 0\n0 1 0\n3 0 1 2\n"), "vertex 0: '0.5' is not an integer (line 10)");
  EXPECT_EQ(ascii("nan.ply", "0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n"), "vertex 1: non-finite value of 'y' (line 11)");
  EXPECT_EQ(ascii("inf.ply", "0 0 0\n-inf 0 0\n0 1 0\n3 0 1 2\n"), "vertex 1: non-finite value of 'x' (line 11)");
  EXPECT_EQ(ascii("overflow.ply", "0 0 0\n1e39 0 0\n0 1 0\n3 0 1 2\n"), "vertex 1: non-finite value of 'x' (line 11)");
  EXPECT_EQ(ascii("range.ply", vertices + "3 0 1 9\n"),
            "face 0: references vertex 9 but there are only 3 vertices (line 13)");
  EXPECT_EQ(ascii("negative.ply", vertices + "3 0 -1 2\n"),
            "face 0: references vertex -1 but there are only 3 vertices (line 13)");
  EXPECT_EQ(ascii("count.ply", vertices + "-1 0 1 2\n"), "face 0: negative list count -1 (line 13)");
  EXPECT_EQ(ascii("index.ply", vertices + "3 0 1.0 2\n"), "face 0: '1.0' is not an integer (line 13)");
  EXPECT_EQ(ascii("absurd.ply", vertices + "100 0 1 2\n"),
            "face 0: a list of 100 vertex indices runs past the end of the file (line 13)");
  EXPECT_EQ(ascii("short.ply", vertices + "3 0 1\n"), "file ends after 0 of the 1 face entries (line 13)");
  EXPECT_EQ(ascii("missing.ply", "0.000 0.000 0\n1.000 0.000 0\n"),
            "file ends after 2 of the 3 vertex entries (line 11)");
  EXPECT_EQ(ascii("lying.ply", "0 0 0\n1 0 0\n"),
            "PLY element 'vertex' claims 3 entries of at least 6 bytes each, but only 12 bytes follow the header "
            "(truncated?)");

  std::string many = "0 0 0\n1 0 0\n0 1 0\n1100";
  for (int i = 0; i < 1100; ++i) {
    many += ' ';
    many += std::to_string(i % 3);
  }
  EXPECT_EQ(problem(write("many.ply",
                          "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                          "property float z\nelement face 1\nproperty list int int vertex_indices\n"
                          "end_header\n" +
                              many + "\n")),
            "face 0: has 1100 corners, more than the 1024 supported (line 13)");

  std::size_t at = 0;
  const std::string range = one_face(
      "binary_little_endian", "uchar uint",
      [](PlyWriter& w) {
        w.list("uchar", "uint", {0, 1, 3});
      },
      &at);
  EXPECT_EQ(
      problem(write("range_le.ply", range)),
      "face 0: references vertex 3 but there are only 3 vertices (byte offset " + std::to_string(at + 1 + 8) + ")");
  const std::string absurd = one_face(
      "binary_big_endian", "int int",
      [](PlyWriter& w) { w.put("int", 1000000).put("int", 0).put("int", 1).put("int", 2); }, &at);
  EXPECT_EQ(problem(write("absurd_be.ply", absurd)),
            "face 0: a list of 1000000 vertex indices runs past the end of the file (byte offset " +
                std::to_string(at) + ")");
  const std::string negative = one_face(
      "binary_little_endian", "short short", [](PlyWriter& w) { w.put("short", -3); }, &at);
  EXPECT_EQ(problem(write("negative_le.ply", negative)),
            "face 0: negative list count -3 (byte offset " + std::to_string(at) + ")");

  PlyWriter nan("binary_big_endian");
  nan.header("element vertex 1").header("property float x").header("property double y").header("property float z");
  nan.header("element face 0").header("property list uchar int vertex_indices");
  nan.put("float", 0).put("double", std::numeric_limits<double>::quiet_NaN()).put("float", 0);
  // The point-cloud check comes first, so give it a face to get as far as the vertex.
  std::string text = nan.str();
  text.replace(text.find("face 0"), 6, "face 1");
  EXPECT_EQ(problem(write("nan_be.ply", text + std::string("\3\0\0\0\0\0\0\0\0\0\0\0\0", 13))),
            "vertex 0: non-finite value of 'y' (byte offset " + std::to_string(nan.header_size() + 4) + ")");
}

TEST_F(PlyLoader, EveryTruncationOfEachEncodingLoadsOrIsRefusedCleanly) {
  for (const char* encoding : kEncodings) {
    SCOPED_TRACE(encoding);
    test::expect_every_prefix_loads_or_throws(dir_ / "cut.ply", pyramid(encoding, std::string(encoding) == "ascii"));
  }
}

TEST_F(PlyLoader, AssimpModelsLoadWithTheirKnownCounts) {
  if (!fs::is_directory(kAssimpPly)) GTEST_SKIP() << "assimp-testmodels not installed";
  struct Known {
    const char* name;
    std::size_t vertices, triangles;
    bool normals, uvs, colors;
  };
  // Triangle counts as `assimp info` reports them; vertices as the files list them (assimp merges some).
  const Known known[] = {{"cube.ply", 8, 12, false, false, false},
                         {"cube_binary.ply", 8, 12, false, false, false},
                         {"cube_uv.ply", 24, 12, true, true, false},
                         {"float-color.ply", 3, 1, false, false, true},
                         {"Wuson.ply", 11184, 3732, true, true, false}};
  testing::internal::CaptureStderr();  // Wuson.ply's credit line lacks "comment"
  for (const Known& k : known) {
    const Mesh m = load_model(kAssimpPly / k.name);
    EXPECT_EQ(m.vertex_count(), k.vertices) << k.name;
    EXPECT_EQ(m.triangle_count(), k.triangles) << k.name;
    EXPECT_EQ(m.normals.size(), k.normals ? k.vertices : 0) << k.name;
    EXPECT_EQ(m.uvs.size(), k.uvs ? k.vertices : 0) << k.name;
    EXPECT_EQ(m.colors.size(), k.colors ? k.vertices : 0) << k.name;
  }
  testing::internal::GetCapturedStderr();
  EXPECT_EQ(load_model(kAssimpPly / "float-color.ply").colors[0], glm::vec4(0, 0, 1, 1));
  // points.ply is a point cloud: four vertices with colours and normals, each a point.
  const Mesh points = load_model(kAssimpPly / "points.ply");
  EXPECT_EQ(points.points, (std::vector<std::uint32_t>{0, 1, 2, 3}));
  EXPECT_EQ(points.colors.size(), 4u);
  EXPECT_EQ(points.normals.size(), 4u);
  EXPECT_EQ(points.colors[1], glm::vec4(1, 0, 1, 1));
  // pond.0.ply has no faces, and is cut short: 70,051 vertices of 31 bytes do not fit in what follows its header.
  EXPECT_EQ(problem(kAssimpPly / "pond.0.ply"),
            "PLY element 'vertex' claims 70051 entries of at least 31 bytes each, but only 2171512 bytes follow the "
            "header (truncated?)");
}

TEST_F(PlyLoader, EveryPlyFileOfTheAssimpModelsLoadsOrThrowsInputError) {
  const fs::path models = kAssimpPly.parent_path();
  if (!fs::is_directory(models)) GTEST_SKIP() << "assimp-testmodels not installed";
  int loaded = 0, refused = 0;
  testing::internal::CaptureStderr();
  for (const auto& entry : fs::recursive_directory_iterator(models)) {
    std::string ext = entry.path().extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (!entry.is_regular_file() || ext != ".ply") continue;
    try {
      const Mesh m = load_model(entry.path());
      EXPECT_NO_THROW(validate(m, entry.path().string())) << entry.path();
      EXPECT_GT(m.triangle_count() + m.point_count(), 0u) << entry.path();
      ++loaded;
    } catch (const InputError& e) {
      EXPECT_EQ(e.source(), entry.path().string());
      ++refused;
    }
  }
  testing::internal::GetCapturedStderr();
  EXPECT_GE(loaded, 6);   // points.ply among them, as a point cloud
  EXPECT_GE(refused, 3);  // issue623.ply, pond.0.ply, invalid/empty.ply
}

}  // namespace
}  // namespace facet::ply_loader_tests
