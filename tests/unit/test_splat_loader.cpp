// test_splat_loader.cpp - splat scenes: the paper's PLY layout (activations, encodings, bad input) and .splat.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "facet/error.hpp"
#include "facet/model_io.hpp"
#include "facet/splats.hpp"
#include "support/load_problem.hpp"
#include "support/scratch_dir.hpp"

namespace facet::splat_loader_tests {
namespace {

// The paper's property order, with `rest` f_rest properties.
std::vector<std::string> names(int rest) {
  std::vector<std::string> n = {"x", "y", "z", "nx", "ny", "nz", "f_dc_0", "f_dc_1", "f_dc_2"};
  for (int k = 0; k < rest; ++k) n.push_back("f_rest_" + std::to_string(k));
  for (const char* p : {"opacity", "scale_0", "scale_1", "scale_2", "rot_0", "rot_1", "rot_2", "rot_3"}) n.push_back(p);
  return n;
}

// A splat PLY of the given entries (one value per property of names(rest)) in `format`.
std::string splat_ply(const std::vector<std::vector<float>>& entries, int rest, const std::string& format,
                      const std::string& extra_header = "") {
  std::string out = "ply\nformat " + format + " 1.0\nelement vertex " + std::to_string(entries.size()) + "\n";
  for (const std::string& n : names(rest)) out += "property float " + n + "\n";
  out += extra_header + "end_header\n";
  for (const std::vector<float>& e : entries) {
    if (format == "ascii") {
      for (float v : e) {
        char text[32];
        std::snprintf(text, sizeof text, "%.9g ", static_cast<double>(v));
        out += text;
      }
      out += "\n";
      continue;
    }
    for (float v : e) {
      std::uint32_t bits;
      std::memcpy(&bits, &v, sizeof bits);
      if (format == "binary_big_endian") bits = __builtin_bswap32(bits);
      out.append(reinterpret_cast<const char*>(&bits), sizeof bits);
    }
  }
  return out;
}

// Degree 1: f_rest_0..8 are red's three coefficients, then green's, then blue's.
std::vector<float> entry(float x, float opacity, float rot_w) {
  std::vector<float> e = {x, 2.0f, 3.0f, 0, 0, 0, 0.1f, 0.2f, 0.3f};
  for (int k = 0; k < 9; ++k) e.push_back(static_cast<float>(k + 1));
  for (float v : {opacity, 0.0f, std::log(2.0f), -1.0f, rot_w, 0.0f, 0.0f, 0.0f}) e.push_back(v);
  return e;
}

class SplatPly : public testing::Test {
 protected:
  void SetUp() override { dir = test::scratch_dir("splat_ply"); }
  std::filesystem::path dir;
};

TEST_F(SplatPly, ReadsThePapersLayoutWithItsActivationsInEveryEncoding) {
  const std::vector<std::vector<float>> entries = {entry(1.0f, 0.0f, 2.0f), entry(-1.0f, 100.0f, -0.5f)};
  std::vector<Mesh> meshes;
  for (const char* format : {"binary_little_endian", "binary_big_endian", "ascii"})
    meshes.push_back(load_model(test::write_file(dir, std::string(format) + ".ply", splat_ply(entries, 9, format))));
  for (const Mesh& mesh : meshes) {
    ASSERT_TRUE(mesh.splats);
    const GaussianSplats& s = *mesh.splats;
    ASSERT_EQ(s.size(), 2u);
    EXPECT_EQ(mesh.positions, s.positions);  // the centres frame the model
    EXPECT_TRUE(mesh.indices.empty() && mesh.points.empty());
    EXPECT_EQ(s.sh_degree, 1);
    EXPECT_EQ(s.positions[1], glm::vec3(-1.0f, 2.0f, 3.0f));
    EXPECT_NEAR(s.opacities[0], 0.5f, 1e-6f);  // sigmoid(0)
    EXPECT_NEAR(s.opacities[1], 1.0f, 1e-6f);
    EXPECT_NEAR(s.scales[0].x, 1.0f, 1e-6f);  // exp
    EXPECT_NEAR(s.scales[0].y, 2.0f, 1e-5f);
    EXPECT_NEAR(s.scales[0].z, std::exp(-1.0f), 1e-6f);
    EXPECT_NEAR(s.rotations[0].w, 1.0f, 1e-6f);  // normalised, w first
    EXPECT_NEAR(s.rotations[1].w, -1.0f, 1e-6f);
    ASSERT_EQ(s.sh.size(), 8u);
    EXPECT_NEAR(s.sh[0].g, 0.2f, 1e-6f);
    // Coefficient k of channel c is f_rest_(c * 3 + k - 1).
    EXPECT_EQ(s.sh[1], glm::vec3(1.0f, 4.0f, 7.0f));
    EXPECT_EQ(s.sh[3], glm::vec3(3.0f, 6.0f, 9.0f));
  }
  for (std::size_t m = 1; m < meshes.size(); ++m) {
    EXPECT_EQ(meshes[m].splats->scales, meshes[0].splats->scales);
    EXPECT_EQ(meshes[m].splats->sh, meshes[0].splats->sh);
  }
}

TEST_F(SplatPly, BadFilesAreRefusedOnOneLineAndBadGaussiansSkipped) {
  const auto refused = [&](const std::string& name, const std::string& bytes) {
    return test::load_problem(test::write_file(dir, name, bytes));
  };
  std::vector<float> ten = entry(0, 0, 1);
  ten.insert(ten.begin() + 18, 0.0f);
  EXPECT_NE(refused("rest.ply", splat_ply({ten}, 10, "ascii")).find("10 f_rest properties"), std::string::npos);
  std::string no_scale = splat_ply({entry(0, 0, 1)}, 9, "ascii");
  no_scale.replace(no_scale.find("property float scale_2"), 22, "property float other_2");
  EXPECT_NE(refused("scale.ply", no_scale).find("'scale_2'"), std::string::npos);
  const std::string binary = splat_ply({entry(0, 0, 1), entry(1, 0, 1)}, 9, "binary_little_endian");
  EXPECT_FALSE(refused("short.ply", binary.substr(0, binary.size() - 5)).empty());
  std::string lying = binary;
  lying.replace(lying.find("vertex 2"), 8, "vertex 2000000000");
  EXPECT_FALSE(refused("lying.ply", lying).empty());
  testing::internal::CaptureStderr();
  EXPECT_NE(refused("none.ply", splat_ply({entry(0, 0, 0)}, 9, "ascii")).find("no Gaussian"), std::string::npos);
  testing::internal::GetCapturedStderr();

  // A zero rotation and a NaN position are skipped with a warning; the rest load.
  std::vector<float> nan_position = entry(0, 0, 1);
  nan_position[0] = std::nanf("");
  testing::internal::CaptureStderr();
  const Mesh mesh = load_model(test::write_file(
      dir, "skips.ply", splat_ply({entry(0, 0, 0), nan_position, entry(5, 0, 1)}, 9, "binary_little_endian")));
  const std::string warnings = testing::internal::GetCapturedStderr();
  ASSERT_TRUE(mesh.splats);
  EXPECT_EQ(mesh.splats->size(), 1u);
  EXPECT_EQ(mesh.splats->positions[0].x, 5.0f);
  EXPECT_NE(warnings.find("zero rotation"), std::string::npos) << warnings;
  EXPECT_NE(warnings.find("not finite"), std::string::npos) << warnings;
}

TEST_F(SplatPly, EveryPrefixLoadsOrIsRefused) {
  const std::string bytes = splat_ply({entry(0, 0, 1), entry(1, 0, 1), entry(2, 0, 1)}, 9, "binary_little_endian");
  test::expect_every_prefix_loads_or_throws(dir / "prefix.ply", bytes, true);
  const std::string text = splat_ply({entry(0, 0, 1), entry(1, 0, 1)}, 9, "ascii");
  test::expect_every_prefix_loads_or_throws(dir / "prefix_text.ply", text, true);
}

// One .splat record: position and linear scales as float32, colour and opacity bytes, rotation bytes q * 128 + 128.
std::string splat_record(glm::vec3 p, glm::vec3 scale, const unsigned char rgba[4], const unsigned char rotation[4]) {
  std::string out;
  for (float v : {p.x, p.y, p.z, scale.x, scale.y, scale.z}) out.append(reinterpret_cast<const char*>(&v), 4);
  out.append(reinterpret_cast<const char*>(rgba), 4);
  out.append(reinterpret_cast<const char*>(rotation), 4);
  return out;
}

TEST_F(SplatPly, SplatFilesDecodeColourOpacityAndRotation) {
  const unsigned char orange[4] = {255, 128, 0, 204}, identity[4] = {255, 128, 128, 128}, none[4] = {128, 128, 128, 128};
  const std::string bytes = splat_record({1, 2, 3}, {0.5f, 0.25f, 0.125f}, orange, identity) +
                            splat_record({4, 5, 6}, {1, 1, 1}, orange, none);
  testing::internal::CaptureStderr();
  const Mesh mesh = load_model(test::write_file(dir, "scene.splat", bytes));
  const std::string warnings = testing::internal::GetCapturedStderr();
  ASSERT_TRUE(mesh.splats);
  const GaussianSplats& s = *mesh.splats;
  ASSERT_EQ(s.size(), 1u);  // the zero rotation is skipped
  EXPECT_NE(warnings.find("zero rotation"), std::string::npos) << warnings;
  EXPECT_EQ(s.positions[0], glm::vec3(1, 2, 3));
  EXPECT_EQ(s.scales[0], glm::vec3(0.5f, 0.25f, 0.125f));
  EXPECT_NEAR(s.opacities[0], 0.8f, 1e-6f);
  EXPECT_NEAR(s.rotations[0].w, 1.0f, 1e-6f);
  EXPECT_EQ(s.sh_degree, 0);
  // The displayed colour, seen from anywhere, is the file's bytes over 255.
  const glm::vec3 shown = splat_color(s, 0, glm::vec3(0, 0, -1));
  EXPECT_NEAR(shown.r, 1.0f, 1e-6f);
  EXPECT_NEAR(shown.g, 128.0f / 255.0f, 1e-6f);
  EXPECT_NEAR(shown.b, 0.0f, 1e-6f);

  EXPECT_NE(test::load_problem(test::write_file(dir, "cut.splat", bytes.substr(0, 40))).find("32-byte"),
            std::string::npos);
  EXPECT_FALSE(test::load_problem(test::write_file(dir, "empty.splat", "")).empty());
}

}  // namespace
}  // namespace facet::splat_loader_tests
