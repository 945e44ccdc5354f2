// test_stl_loader.cpp - unit tests for load_model() on STL: binary and ASCII written on the fly, welding, bad input.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "facet/error.hpp"
#include "facet/model_io.hpp"
#include "support/load_problem.hpp"
#include "support/scratch_dir.hpp"

namespace facet::stl_loader_tests {
namespace {

namespace fs = std::filesystem;

const fs::path kAssimpStl = "/usr/share/assimp/models/STL";

using Triangle = std::array<glm::vec3, 3>;

// The unit cube's 12 triangles, counter-clockwise seen from outside.
std::vector<Triangle> cube() {
  const glm::vec3 c[8] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  const int quads[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  std::vector<Triangle> out;
  for (const auto& q : quads) {
    out.push_back({c[q[0]], c[q[1]], c[q[2]]});
    out.push_back({c[q[0]], c[q[2]], c[q[3]]});
  }
  return out;
}

void put_u32(std::string& s, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) s.push_back(static_cast<char>(v >> (8 * i)));
}
void put_float(std::string& s, float f) {
  std::uint32_t bits;
  std::memcpy(&bits, &f, 4);
  put_u32(s, bits);
}

std::string binary_stl(const std::vector<Triangle>& triangles, const std::string& header = "facet test") {
  std::string s = header.substr(0, 80);
  s.resize(80, '\0');
  put_u32(s, static_cast<std::uint32_t>(triangles.size()));
  for (const Triangle& t : triangles) {
    for (int k = 0; k < 3; ++k) put_float(s, 0.0f);  // normal: ignored
    for (const glm::vec3& p : t)
      for (int k = 0; k < 3; ++k) put_float(s, p[k]);
    s += std::string(2, '\0');
  }
  return s;
}

std::string ascii_facets(const std::vector<Triangle>& triangles) {
  std::string s;
  for (const Triangle& t : triangles) {
    s += "  facet normal 0 0 1\n    outer loop\n";
    for (const glm::vec3& p : t)
      s += "      vertex " + std::to_string(p.x) + " " + std::to_string(p.y) + " " + std::to_string(p.z) + "\n";
    s += "    endloop\n  endfacet\n";
  }
  return s;
}

std::string ascii_stl(const std::vector<Triangle>& triangles, const std::string& name = "cube") {
  return "solid " + name + "\n" + ascii_facets(triangles) + "endsolid " + name + "\n";
}

class StlLoader : public ::testing::Test {
 protected:
  fs::path write(const std::string& name, const std::string& bytes) const {
    return test::write_file(dir_, name, bytes);
  }
  static std::string problem(const fs::path& p) { return test::load_problem(p); }
  void SetUp() override { dir_ = test::scratch_dir("models"); }
  fs::path dir_;
};

// The mesh's triangles as positions, in order, each starting at its first corner.
std::vector<Triangle> triangles_of(const Mesh& m) {
  std::vector<Triangle> out;
  for (std::size_t i = 0; i < m.indices.size(); i += 3)
    out.push_back({m.positions[m.indices[i]], m.positions[m.indices[i + 1]], m.positions[m.indices[i + 2]]});
  return out;
}

TEST_F(StlLoader, BinaryCubeIsWeldedToEightVerticesInFileOrder) {
  const Mesh m = load_model(write("cube.stl", binary_stl(cube())));
  EXPECT_EQ(m.vertex_count(), 8u);
  EXPECT_EQ(m.triangle_count(), 12u);
  EXPECT_EQ(triangles_of(m), cube());  // order and winding kept
  EXPECT_TRUE(m.normals.empty());      // facet normals are not used: the renderer computes crease normals
  EXPECT_TRUE(m.uvs.empty());
  EXPECT_TRUE(m.colors.empty());
  EXPECT_EQ(m.indices[0], 0u);  // vertices numbered in order of first use
  EXPECT_EQ(m.indices[1], 1u);
  EXPECT_EQ(m.indices[2], 2u);
}

TEST_F(StlLoader, AsciiCubeGivesTheSameMeshAsBinary) {
  const Mesh b = load_model(write("b.stl", binary_stl(cube())));
  const Mesh a = load_model(write("a.stl", ascii_stl(cube())));
  EXPECT_EQ(a.positions, b.positions);
  EXPECT_EQ(a.indices, b.indices);
}

TEST_F(StlLoader, BinaryWhoseHeaderBeginsWithSolidIsReadAsBinary) {
  const Mesh m = load_model(write("solid.stl", binary_stl(cube(), "solid cube exported by a CAD program")));
  EXPECT_EQ(m.vertex_count(), 8u);
  EXPECT_EQ(triangles_of(m), cube());
}

TEST_F(StlLoader, EverySolidOfAnAsciiFileIsRead) {
  const std::vector<Triangle> all = cube();
  const std::vector<Triangle> first(all.begin(), all.begin() + 5), second(all.begin() + 5, all.end());
  const std::string text = ascii_stl(first, "part one") + "solid empty\nendsolid empty\n" + ascii_stl(second, "");
  const Mesh m = load_model(write("solids.stl", text));
  EXPECT_EQ(triangles_of(m), all);
  EXPECT_EQ(m.vertex_count(), 8u);
}

TEST_F(StlLoader, AsciiKeywordsInAnyCaseAndAnyWhitespace) {
  const std::string text =
      "SOLID Mixed\r\n\tFACET NORMAL 0 0 1\r\nOuter Loop\r\nVERTEX 0 0 0 vertex 1 0 0\tvertex +0 1e0 0\r\n"
      "ENDLOOP endfacet\r\nEndSolid Mixed";
  const Mesh m = load_model(write("mixed.stl", text));
  ASSERT_EQ(m.triangle_count(), 1u);
  EXPECT_EQ(triangles_of(m)[0], (Triangle{glm::vec3(0, 0, 0), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0)}));
}

TEST_F(StlLoader, WeldsExactlyEqualPositionsOnlyWithBothZerosAsOne) {
  const float tiny = std::nextafter(1.0f, 2.0f);
  const std::vector<Triangle> t = {{glm::vec3(0, 0, 0), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0)},
                                   {glm::vec3(-0.0f, 0, -0.0f), glm::vec3(tiny, 0, 0), glm::vec3(0, 1, 0)}};
  const Mesh m = load_model(write("weld.stl", binary_stl(t)));
  EXPECT_EQ(m.indices, (std::vector<std::uint32_t>{0, 1, 2, 0, 3, 2}));
  EXPECT_EQ(m.vertex_count(), 4u);
}

TEST_F(StlLoader, DegenerateFacetsAreKept) {
  const std::vector<Triangle> t = {{glm::vec3(0, 0, 0), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0)},
                                   {glm::vec3(0, 0, 0), glm::vec3(0, 0, 0), glm::vec3(0, 1, 0)}};
  const Mesh m = load_model(write("degenerate.stl", binary_stl(t)));
  EXPECT_EQ(m.indices, (std::vector<std::uint32_t>{0, 1, 2, 0, 0, 2}));
}

TEST_F(StlLoader, ManyVerticesGrowTheWeldingTable) {
  // A strip of 20,000 facets has 20,002 distinct corners: more than the table's first guess (half the facets).
  std::vector<Triangle> strip;
  for (int i = 0; i < 20000; ++i) {
    const float x = static_cast<float>(i / 2);
    if (i % 2 == 0) strip.push_back({glm::vec3(x, 0, 0), glm::vec3(x + 1, 0, 0), glm::vec3(x, 1, 0)});
    else strip.push_back({glm::vec3(x + 1, 0, 0), glm::vec3(x + 1, 1, 0), glm::vec3(x, 1, 0)});
  }
  const Mesh m = load_model(write("strip.stl", binary_stl(strip)));
  EXPECT_EQ(m.vertex_count(), 20002u);
  EXPECT_EQ(triangles_of(m), strip);
}

TEST_F(StlLoader, ChosenByContentWhenTheExtensionSaysNothing) {
  EXPECT_EQ(load_model(write("binary_no_extension", binary_stl(cube()))).vertex_count(), 8u);
  EXPECT_EQ(load_model(write("ascii.model", ascii_stl(cube()))).vertex_count(), 8u);
  EXPECT_EQ(load_model(write("UPPER.STL", ascii_stl(cube()))).vertex_count(), 8u);
}

TEST_F(StlLoader, BadFilesThrowInputErrorNamingThePath) {
  EXPECT_EQ(problem(write("empty_solid.stl", "solid x\nendsolid x\n")),
            "no triangles found (ASCII STL without facets)");
  EXPECT_EQ(problem(write("zero.stl", binary_stl({}))), "no triangles found (binary STL with a triangle count of 0)");
  EXPECT_EQ(problem(write("short.stl", "hello")),
            "not an STL file: 5 bytes is too short for a binary STL (84 or more) and there is no 'solid' keyword");
  std::string cut = binary_stl(cube());
  cut.resize(cut.size() - 1);
  EXPECT_EQ(problem(write("cut.stl", cut)),
            "binary STL header claims 12 triangles (684 bytes) but the file has 683 "
            "bytes (truncated?)");
  std::string cut_solid = binary_stl(cube(), "solid cube");
  cut_solid.resize(cut_solid.size() - 50);
  EXPECT_EQ(problem(write("cut_solid.stl", cut_solid)),
            "binary STL header claims 12 triangles (684 bytes) but the file has 634 bytes (truncated?)");

  const std::string facet = "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n";
  EXPECT_EQ(problem(write("word.stl", facet + "vertex 0 abc 0\nendloop\nendfacet\nendsolid\n")),
            "expected a number on line 6, found 'abc'");
  EXPECT_EQ(problem(write("four.stl", facet + "vertex 0 1 0\nvertex 1 1 0\nendloop\nendfacet\nendsolid\n")),
            "expected 'endloop' on line 7, found 'vertex'");
  EXPECT_EQ(problem(write("open.stl", facet + "vertex 0 1 0\nendloop\nendfacet\n")),
            "file ends inside a solid (no 'endsolid')");
  EXPECT_EQ(problem(write("midway.stl", facet)), "expected 'vertex' but the file ends");
  EXPECT_EQ(problem(write("nan.stl", facet + "vertex nan 1 0\nendloop\nendfacet\nendsolid\n")),
            "non-finite vertex position on line 6");
  EXPECT_EQ(problem(write("huge.stl", facet + "vertex 1e39 1 0\nendloop\nendfacet\nendsolid\n")),
            "non-finite vertex position on line 6");
  EXPECT_EQ(problem(write("junk.stl", "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0 1\n")),
            "expected 'vertex' on line 4, found '1'");
  EXPECT_EQ(problem(write("after.stl", "solid s\nendsolid s\nfacet\n")), "expected 'solid' on line 3, found 'facet'");

  std::vector<Triangle> bad = cube();
  bad[1][2].y = std::numeric_limits<float>::infinity();
  EXPECT_EQ(problem(write("inf.stl", binary_stl(bad))),
            "non-finite vertex position in triangle 1 (byte offset 170)");  // 84 + 50 + 12 + 2 * 12
}

TEST_F(StlLoader, EveryTruncationOfABinaryFileIsRefusedCleanly) {
  test::expect_every_prefix_loads_or_throws(dir_ / "cut.stl", binary_stl(cube()));
  test::expect_every_prefix_loads_or_throws(dir_ / "cut.stl", binary_stl(cube(), "solid cube"));
}

TEST_F(StlLoader, EveryTruncationOfAnAsciiFileLoadsOrIsRefusedCleanly) {
  const std::vector<Triangle> t = cube();
  test::expect_every_prefix_loads_or_throws(dir_ / "cut.stl", ascii_stl({t[0], t[1], t[2]}));
}

TEST_F(StlLoader, AssimpModelsLoadWithTheirKnownCounts) {
  if (!fs::is_directory(kAssimpStl)) GTEST_SKIP() << "assimp-testmodels not installed";
  struct Known {
    const char* name;
    std::size_t vertices, triangles;
  };
  // Triangle counts as `assimp info` reports them; vertex counts are distinct positions (assimp also splits by normal).
  const Known known[] = {
      {"Spider_binary.stl", 722, 1368},       {"Spider_ascii.stl", 722, 1368},         {"Wuson.stl", 2117, 3732},
      {"3DSMaxExport.STL", 1042, 2000},       {"sphereWithHole.stl", 146, 285},        {"triangle.stl", 3, 1},
      {"triangle_with_two_solids.stl", 6, 2}, {"triangle_with_empty_solid.stl", 3, 1}, {"formatDetection", 3, 1}};
  for (const Known& k : known) {
    const Mesh m = load_model(kAssimpStl / k.name);
    EXPECT_EQ(m.vertex_count(), k.vertices) << k.name;
    EXPECT_EQ(m.triangle_count(), k.triangles) << k.name;
    EXPECT_FALSE(bounds(m).empty()) << k.name;
  }
  // The same spider in both encodings: the ASCII file's six decimals are close to the binary's floats.
  const Mesh a = load_model(kAssimpStl / "Spider_ascii.stl"), b = load_model(kAssimpStl / "Spider_binary.stl");
  EXPECT_EQ(a.indices, b.indices);
  for (std::size_t i = 0; i < a.positions.size(); ++i)
    EXPECT_LT(glm::distance(a.positions[i], b.positions[i]), 1e-5f) << i;
}

TEST_F(StlLoader, EveryStlFileOfTheAssimpModelsLoadsOrThrowsInputError) {
  const fs::path models = kAssimpStl.parent_path();
  if (!fs::is_directory(models)) GTEST_SKIP() << "assimp-testmodels not installed";
  int loaded = 0, files = 0;
  for (const auto& entry : fs::recursive_directory_iterator(models)) {
    std::string ext = entry.path().extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (!entry.is_regular_file() || ext != ".stl") continue;
    ++files;
    try {
      const Mesh m = load_model(entry.path());
      EXPECT_NO_THROW(validate(m, entry.path().string())) << entry.path();
      EXPECT_GT(m.triangle_count(), 0u) << entry.path();
      ++loaded;
    } catch (const InputError& e) {
      EXPECT_EQ(e.source(), entry.path().string());
    }
  }
  EXPECT_GE(files, 8);
  EXPECT_GE(loaded, 8);
}

}  // namespace
}  // namespace facet::stl_loader_tests
