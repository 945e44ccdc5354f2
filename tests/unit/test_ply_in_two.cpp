// test_ply_in_two.cpp - an ASCII PLY read in two halves on two threads gives what one thread gives, or is read by one.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "facet/error.hpp"
#include "facet/mesh.hpp"
#include "facet/warnings.hpp"
#include "job/io/loaders.hpp"

namespace facet::ply_in_two_tests {
namespace {

namespace fs = std::filesystem;

// What a read produced: the mesh and warnings, or the error.
struct Outcome {
  std::optional<Mesh> mesh;
  std::vector<std::string> warnings;
  std::string error;
  bool in_two = false;
};

Outcome read(const std::string& bytes, int threads) {
  Outcome out;
  WarningCapture capture;
  try {
    out.mesh = load_ply(bytes, "test.ply", threads, 0, &out.in_two);
  } catch (const InputError& e) {
    out.error = e.what();
  }
  out.warnings = capture.messages();
  return out;
}

// Bit-for-bit equality of every array a PLY fills.
void expect_same(const Outcome& one, const Outcome& two, const std::string& what) {
  EXPECT_EQ(one.error, two.error) << what;
  EXPECT_EQ(one.warnings, two.warnings) << what;
  ASSERT_EQ(one.mesh.has_value(), two.mesh.has_value()) << what;
  if (!one.mesh) return;
  const Mesh& a = *one.mesh;
  const Mesh& b = *two.mesh;
  EXPECT_EQ(a.positions, b.positions) << what;
  EXPECT_EQ(a.normals, b.normals) << what;
  EXPECT_EQ(a.colors, b.colors) << what;
  EXPECT_EQ(a.uvs, b.uvs) << what;
  EXPECT_EQ(a.indices, b.indices) << what;
  EXPECT_EQ(a.face_ids, b.face_ids) << what;
}

// A random ASCII PLY of one entry per line: vertices with normals, colours and uvs, faces of 1 to 6 corners (some
// concave, some dropped) behind a per-face flag, so halves split polygons, dropped faces and renumbering.
std::string random_ply(std::mt19937& rng, int vertices, int faces, const char* line_break) {
  std::ostringstream out;
  out << "ply" << line_break << "format ascii 1.0" << line_break << "element vertex " << vertices << line_break;
  for (const char* p : {"x", "y", "z", "nx", "ny", "nz"}) out << "property float " << p << line_break;
  for (const char* p : {"red", "green", "blue"}) out << "property uchar " << p << line_break;
  out << "property float u" << line_break << "property float v" << line_break;
  out << "element face " << faces << line_break << "property uchar flags" << line_break
      << "property list uchar int vertex_indices" << line_break << "end_header" << line_break;
  std::uniform_real_distribution<float> coordinate(-10, 10);
  std::uniform_int_distribution<int> byte(0, 255), vertex(0, vertices - 1), corners(1, 6), percent(0, 99);
  for (int v = 0; v < vertices; ++v) {
    for (int k = 0; k < 6; ++k) out << coordinate(rng) << ' ';
    for (int k = 0; k < 3; ++k) out << byte(rng) << ' ';
    out << coordinate(rng) << ' ' << coordinate(rng) << line_break;
  }
  for (int f = 0; f < faces; ++f) {
    // Mostly triangles, as real files are; a few polygons and a few faces too small to keep.
    const int n = percent(rng) < 85 ? 3 : corners(rng);
    out << byte(rng) << ' ' << n;
    for (int k = 0; k < n; ++k) out << ' ' << vertex(rng);
    out << line_break;
  }
  return out.str();
}

TEST(PlyInTwo, RandomFilesReadAsOneThreadReadsThem) {
  std::mt19937 rng(2026);
  for (int trial = 0; trial < 40; ++trial) {
    const int vertices = 1 + static_cast<int>(rng() % 300), faces = 1 + static_cast<int>(rng() % 400);
    const std::string bytes = random_ply(rng, vertices, faces, trial % 4 == 3 ? "\r\n" : "\n");
    const Outcome one = read(bytes, 1), two = read(bytes, 2);
    EXPECT_FALSE(one.in_two);
    EXPECT_TRUE(two.in_two) << "trial " << trial << ": " << two.error;
    expect_same(one, two, "trial " + std::to_string(trial));
  }
}

// Shapes the two-thread reader does not take: it must leave them to one thread, which reads (or refuses) them as
// always.
TEST(PlyInTwo, OtherShapesFallBackToOneThread) {
  std::mt19937 rng(7);
  const std::string good = random_ply(rng, 50, 80, "\n");
  const std::size_t body = good.find("end_header\n") + 11;
  const std::size_t first_face = [&] {
    std::size_t p = body;
    for (int v = 0; v < 50; ++v) p = good.find('\n', p) + 1;
    return p;
  }();
  const std::size_t second_line = good.find('\n', body) + 1;
  struct Case {
    const char* name;
    std::string bytes;
  };
  std::string joined = good;  // two vertices on one line
  joined[second_line - 1] = ' ';
  std::string split = good;  // one vertex over two lines
  split[good.find(' ', body)] = '\n';
  std::string out_of_range = good;  // an index past the vertices, in the second half of the faces
  out_of_range.insert(good.rfind('\n', good.size() - 2) + 1, "0 3 0 1 9999\n");
  const Case cases[] = {
      {"blank line among the vertices", good.substr(0, second_line) + "\n" + good.substr(second_line)},
      {"blank line among the faces", good.substr(0, first_face) + "\n" + good.substr(first_face)},
      {"two vertices on one line", joined},
      {"a vertex over two lines", split},
      {"text after the last face", good + "trailing words\n"},
      {"missing last face", good.substr(0, good.rfind('\n', good.size() - 2) + 1)},
      {"an index out of range in the last face", out_of_range},
      {"not a number", good.substr(0, second_line) + "1 2 x 0 0 1 0 0 0 0 0\n" + good.substr(second_line)},
  };
  for (const Case& c : cases) {
    const Outcome one = read(c.bytes, 1), two = read(c.bytes, 2);
    EXPECT_FALSE(two.in_two) << c.name;
    expect_same(one, two, c.name);
  }
  // The good file itself does go to two threads.
  EXPECT_TRUE(read(good, 2).in_two);
}

TEST(PlyInTwo, AssimpModelsReadAsOneThreadReadsThem) {
  const fs::path folder = "/usr/share/assimp/models/PLY";
  ASSERT_TRUE(fs::is_directory(folder)) << "assimp-testmodels is not installed";
  int ascii = 0;
  for (const fs::directory_entry& entry : fs::directory_iterator(folder)) {
    if (entry.path().extension() != ".ply") continue;
    std::ifstream in(entry.path(), std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (bytes.find("format ascii") == std::string::npos) continue;
    ++ascii;
    expect_same(read(bytes, 1), read(bytes, 2), entry.path().filename().string());
  }
  EXPECT_GE(ascii, 3);
}

}  // namespace
}  // namespace facet::ply_in_two_tests
