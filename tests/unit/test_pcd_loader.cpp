// test_pcd_loader.cpp - load_pcd: PCL's PCD files in their three encodings, their fields and their bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "facet/error.hpp"
#include "facet/model_io.hpp"
#include "job/io/loaders.hpp"
#include "support/scratch_dir.hpp"

namespace facet::pcd_loader_tests {
namespace {

std::string header(const std::string& fields, const std::string& sizes, const std::string& types, int points,
                   const std::string& data, const std::string& counts = "") {
  return "# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\nFIELDS " + fields + "\nSIZE " + sizes +
         "\nTYPE " + types + (counts.empty() ? "" : "\nCOUNT " + counts) + "\nWIDTH " + std::to_string(points) +
         "\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " + std::to_string(points) + "\nDATA " + data + "\n";
}

template <class T>
void put(std::string& out, T value) {
  char bytes[sizeof value];
  std::memcpy(bytes, &value, sizeof value);
  out.append(bytes, sizeof value);
}

// An LZF stream of literal runs (a control byte n < 32, then n + 1 bytes): valid for any data.
std::string literal_lzf(const std::string& plain) {
  std::string out;
  for (std::size_t i = 0; i < plain.size(); i += 32) {
    const std::string run = plain.substr(i, 32);
    out += static_cast<char>(run.size() - 1);
    out += run;
  }
  return out;
}

std::string problem(const std::string& bytes) {
  try {
    (void)load_pcd(bytes, "cloud.pcd");
  } catch (const InputError& e) {
    EXPECT_EQ(e.source(), "cloud.pcd");
    return e.problem();
  }
  return "";
}

TEST(PcdLoader, AsciiPointsWithPackedColoursSkipNaNPositions) {
  // rgb as PCL writes it: the colour's bits read as a float (0x00ff8000 is about 2.35e-38).
  float packed;
  const std::uint32_t orange = 0x00ff8000u;
  std::memcpy(&packed, &orange, sizeof packed);
  char value[64];
  std::snprintf(value, sizeof value, "%.9g", static_cast<double>(packed));
  const std::string text = header("x y z rgb", "4 4 4 4", "F F F F", 3, "ascii") + "1 2 3 " + value +
                           "\nnan nan nan " + value + "\n-4.5 0 1e2 0\n";
  const Mesh m = load_pcd(text, "c.pcd");
  ASSERT_EQ(m.positions.size(), 2u);
  EXPECT_EQ(m.positions[0], glm::vec3(1, 2, 3));
  EXPECT_EQ(m.positions[1], glm::vec3(-4.5f, 0, 100));
  EXPECT_EQ(m.points, (std::vector<std::uint32_t>{0, 1}));
  ASSERT_EQ(m.colors.size(), 2u);
  EXPECT_EQ(m.colors[0], glm::vec4(1, 128 / 255.0f, 0, 1));
  EXPECT_EQ(m.colors[1], glm::vec4(0, 0, 0, 1));
  EXPECT_TRUE(m.normals.empty());
  EXPECT_EQ(m.triangle_count(), 0u);
}

// A binary cloud of x y z, a 3-element field the reader skips, a 1-byte intensity and rgba as an unsigned.
std::string binary_points(std::string& by_field) {
  const float xyz[2][3] = {{1, 2, 3}, {-1, 0.5f, 8}};
  const std::uint32_t rgba[2] = {0xffff0000u, 0x8000ff00u};  // 0xAARRGGBB
  std::string rows;
  std::string fields[6];
  for (int i = 0; i < 2; ++i) {
    for (int c = 0; c < 3; ++c) put(rows, xyz[i][c]), put(fields[c], xyz[i][c]);
    for (int c = 0; c < 3; ++c) put(rows, 0.25f * static_cast<float>(c)), put(fields[3], 0.25f * static_cast<float>(c));
    put(rows, static_cast<std::uint8_t>(7 * i)), put(fields[4], static_cast<std::uint8_t>(7 * i));
    put(rows, rgba[i]), put(fields[5], rgba[i]);
  }
  by_field.clear();
  for (const std::string& f : fields) by_field += f;
  return rows;
}

TEST(PcdLoader, BinaryAndCompressedReadTheSameCloud) {
  std::string by_field;
  const std::string rows = binary_points(by_field);
  const std::string fields = "x y z fpfh intensity rgba", sizes = "4 4 4 4 1 4", types = "F F F F U U";
  const Mesh binary = load_pcd(header(fields, sizes, types, 2, "binary", "1 1 1 3 1 1") + rows, "b.pcd");
  ASSERT_EQ(binary.positions.size(), 2u);
  EXPECT_EQ(binary.positions[1], glm::vec3(-1, 0.5f, 8));
  ASSERT_EQ(binary.colors.size(), 2u);
  EXPECT_EQ(binary.colors[0], glm::vec4(1, 0, 0, 1));
  EXPECT_EQ(binary.colors[1], glm::vec4(0, 1, 0, 1));
  std::string compressed = header(fields, sizes, types, 2, "binary_compressed", "1 1 1 3 1 1");
  const std::string lzf = literal_lzf(by_field);
  put(compressed, static_cast<std::uint32_t>(lzf.size()));
  put(compressed, static_cast<std::uint32_t>(by_field.size()));
#if defined(FACET_NO_LZF)
  EXPECT_EQ(problem(compressed + lzf), "binary_compressed PCD data is not read in this build (no LZF)");
#else
  const Mesh unpacked = load_pcd(compressed + lzf, "c.pcd");
  EXPECT_EQ(unpacked.positions, binary.positions);
  EXPECT_EQ(unpacked.colors, binary.colors);
  // A back reference before the first byte.
  EXPECT_EQ(problem(compressed + std::string(1, '\xe0') + lzf.substr(1)), "the compressed data is corrupt");
#endif
}

TEST(PcdLoader, IntensityIsKeptPerPoint) {
  const std::string text = header("x y z intensity", "4 4 4 4", "F F F F", 3, "ascii") +
                           "1 2 3 40\nnan 0 0 50\n4 5 6 nan\n";
  const Mesh m = load_pcd(text, "i.pcd");
  ASSERT_EQ(m.positions.size(), 2u);  // the NaN position is skipped with its intensity
  EXPECT_EQ(m.intensities, (std::vector<float>{40, 0}));  // a NaN intensity reads as 0
}

TEST(PcdLoader, NormalsAreReadWithTheirThreeFields) {
  std::string body = header("x y z normal_x normal_y normal_z curvature", "4 4 4 4 4 4 4", "F F F F F F F", 1,
                            "binary");
  for (const float v : {1.0f, 1.0f, 1.0f, 0.0f, 0.6f, 0.8f, 0.5f}) put(body, v);
  const Mesh m = load_pcd(body, "n.pcd");
  ASSERT_EQ(m.normals.size(), 1u);
  EXPECT_EQ(m.normals[0], glm::vec3(0, 0.6f, 0.8f));
}

TEST(PcdLoader, BadInputIsOneLineNamingTheProblem) {
  const std::string xyz = header("x y z", "4 4 4", "F F F", 2, "binary");
  EXPECT_EQ(problem("VERSION 0.7\nFIELDS x y z\n"), "no DATA line: not a PCD file, or its header is cut short");
  EXPECT_EQ(problem(header("a b c", "4 4 4", "F F F", 1, "ascii") + "1 2 3\n"), "the fields have no x, y and z");
  EXPECT_EQ(problem(xyz + std::string(12, '\0')),
            "truncated: 2 points of 12 bytes need 24, 12 follow the header");
  EXPECT_EQ(problem(header("x y z", "4 4", "F F F", 1, "ascii")),
            "3 fields, but SIZE, TYPE or COUNT gives another number");
  EXPECT_EQ(problem(header("x y z", "4 4 3", "F F F", 1, "ascii")), "field 'z' has SIZE 3 for TYPE F");
  EXPECT_EQ(problem(header("x y z", "4 4 4", "F F Q", 1, "ascii")), "field 'z' has TYPE 'Q' (F, I or U)");
  EXPECT_EQ(problem(header("x y z", "4 4 4", "F F F", 1, "ascii", "1 0 1")), "field 'y' has COUNT 0");
  EXPECT_EQ(problem(header("x y z", "4 4 4", "F F F", 1, "zip") + "x"),
            "DATA 'zip' (ascii, binary or binary_compressed)");
  EXPECT_EQ(problem(header("x y z", "4 4 4", "F F F", 2, "ascii") + "1 2 3\n4 5 x\n"), "point 1: 'x' is not a number");
  EXPECT_EQ(problem(header("x y z", "4 4 4", "F F F", 2, "ascii") + "1 2 3\n4 5 \n"),
            "the data ends after 1 of 2 points");
  EXPECT_EQ(problem(header("x y z", "4 4 4", "F F F", 100000000, "ascii") + "1 2 3\n"),
            "truncated: 100000000 points of 3 values in 6 bytes of text");
  EXPECT_EQ(problem(header("x y z", "4 4 4", "F F F", 1, "ascii") + "nan 0 0\n"),
            "nothing to draw (1 points, none with a position)");
  EXPECT_EQ(problem("VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nPOINTS 999999999999\nDATA ascii\n"),
            "POINTS '999999999999' is not a count from 0 to 134217728");
  EXPECT_EQ(problem("VERSION 0.7\nBOGUS 1\nDATA ascii\n"), "not a PCD header: unknown line 'BOGUS'");
#if !defined(FACET_NO_LZF)
  std::string lying = header("x y z", "4 4 4", "F F F", 1000000, "binary_compressed");
  put(lying, std::uint32_t{2}), put(lying, std::uint32_t{12000000}), lying += std::string("\x01\x00\x00", 3);
  EXPECT_EQ(problem(lying), "the compressed data cannot expand to its claim");
  std::string mismatch = header("x y z", "4 4 4", "F F F", 1, "binary_compressed");
  put(mismatch, std::uint32_t{13}), put(mismatch, std::uint32_t{16}), mismatch += std::string(13, '\0');
  EXPECT_EQ(problem(mismatch), "the compressed data expands to 16 bytes, where 1 points of 12 bytes need 12");
#endif
}

TEST(PcdLoader, ReadModelKnowsTheExtensionAndTheHeader) {
  const std::filesystem::path dir = test::scratch_dir("pcd");
  const std::string cloud = header("x y z", "4 4 4", "F F F", 2, "ascii") + "0 0 0\n1 1 1\n";
  for (const char* name : {"cloud.pcd", "cloud.dat"}) {
    const std::filesystem::path path = dir / name;
    std::FILE* f = std::fopen(path.c_str(), "wb");
    ASSERT_NE(f, nullptr);
    std::fwrite(cloud.data(), 1, cloud.size(), f);
    std::fclose(f);
    std::string format;
    const Model model = read_model(path, format);
    ASSERT_EQ(model.meshes.size(), 1u) << name;
    EXPECT_EQ(model.meshes[0].point_count(), 2u) << name;
    EXPECT_EQ(format, "PCD") << name;
  }
}

}  // namespace
}  // namespace facet::pcd_loader_tests
