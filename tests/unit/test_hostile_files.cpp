// test_hostile_files.cpp - untrusted models: the files they name stay in their folder, and no count makes facet
// allocate, read or walk without bound.
#include <sys/resource.h>
#include <sys/stat.h>

#include <chrono>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "facet/error.hpp"
#include "facet/image_io.hpp"
#include "facet/model_io.hpp"
#include "facet/warnings.hpp"
#include "support/scratch_dir.hpp"

namespace facet::hostile_files_tests {
namespace {

namespace fs = std::filesystem;

// One triangle whose 36 bytes of positions live in the buffer file `uri`.
std::string triangle_gltf(const std::string& uri) {
  return R"({"asset":{"version":"2.0"},"buffers":[{"byteLength":36,"uri":")" + uri +
         R"("}],"bufferViews":[{"buffer":0,"byteLength":36}],"accessors":[{"bufferView":0,"componentType":5126,)"
         R"("count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]}],"meshes":[{"primitives":[{"attributes":)"
         R"({"POSITION":0}}]}],"nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}],"scene":0})";
}

void write_file(const fs::path& path, const std::string& bytes) {
  fs::create_directories(path.parent_path());
  std::ofstream(path, std::ios::binary) << bytes;
}

std::string triangle_positions() {
  const float xyz[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  return std::string(reinterpret_cast<const char*>(xyz), sizeof xyz);
}

// The InputError's problem (after "<path>: ") for loading path, or "" when it loads.
std::string problem(const fs::path& path, const LoadOptions& options = {}) {
  try {
    (void)read_model(path, options);
    return "";
  } catch (const InputError& e) {
    return e.problem();
  }
}

class HostileFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = test::scratch_dir("hostile");
    write_file(dir_ / "outside.bin", triangle_positions());  // a valid buffer, outside the model's folder
  }
  fs::path dir_;
};

TEST_F(HostileFiles, GltfBuffersOutsideTheFolderAreNotRead) {
  const fs::path model = dir_ / "model" / "climbs.gltf";
  write_file(model, triangle_gltf("../outside.bin"));
  // Confined: "../outside.bin" is looked for as model/outside.bin, which does not exist.
  EXPECT_NE(problem(model), "");
  LoadOptions external;
  external.allow_external_files = true;
  EXPECT_EQ(problem(model, external), "");

  const fs::path absolute = dir_ / "model" / "absolute.gltf";
  write_file(absolute, triangle_gltf((dir_ / "outside.bin").string()));
  EXPECT_NE(problem(absolute), "");
  EXPECT_EQ(problem(absolute, external), "");
  write_file(dir_ / "passwd.gltf", triangle_gltf("/etc/passwd"));
  EXPECT_NE(problem(dir_ / "passwd.gltf"), "");

  // The file name beside the model is read instead, as for a model made on another machine.
  write_file(dir_ / "model" / "outside.bin", triangle_positions());
  {
    WarningCapture warnings;
    EXPECT_EQ(problem(model), "");
    ASSERT_FALSE(warnings.messages().empty());
    EXPECT_NE(warnings.messages()[0].find("lies outside the model's folder"), std::string::npos)
        << warnings.messages()[0];
  }
  // A link inside the folder that leads out of it is not followed.
  fs::remove(dir_ / "model" / "outside.bin");
  fs::create_symlink(dir_ / "outside.bin", dir_ / "model" / "linked.bin");
  const fs::path linked = dir_ / "model" / "linked.gltf";
  write_file(linked, triangle_gltf("linked.bin"));
  EXPECT_NE(problem(linked), "");
  EXPECT_EQ(problem(linked, external), "");
}

TEST_F(HostileFiles, DevicesAndFifosAreNeverRead) {
  // A model whose material library and texture are /dev/zero, and a FIFO with no writer: each ends at once.
  write_file(dir_ / "dev.obj", "mtllib /dev/zero\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  write_file(dir_ / "tex.obj", "mtllib tex.mtl\nusemtl m\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  write_file(dir_ / "tex.mtl", "newmtl m\nKd 1 1 1\nmap_Kd /dev/zero\n");
  ASSERT_EQ(::mkfifo((dir_ / "fifo.obj").c_str(), 0600), 0);
  ASSERT_EQ(::mkfifo((dir_ / "fifo.bin").c_str(), 0600), 0);
  write_file(dir_ / "fifo.gltf", triangle_gltf("fifo.bin"));
  const auto start = std::chrono::steady_clock::now();
  for (const LoadOptions& options : {LoadOptions{}, LoadOptions{.allow_external_files = true}}) {
    WarningCapture warnings;
    EXPECT_EQ(problem(dir_ / "dev.obj", options), "");
    EXPECT_EQ(problem(dir_ / "tex.obj", options), "");
    const Mesh textured = load_model(dir_ / "tex.obj", options);
    ASSERT_EQ(textured.materials.size(), 1u);
    EXPECT_EQ(textured.materials[0].diffuse_texture, "");
    EXPECT_EQ(problem(dir_ / "fifo.obj", options), "not a regular file");
    EXPECT_NE(problem(dir_ / "fifo.gltf", options), "");
    EXPECT_GE(warnings.messages().size(), 2u);
  }
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(10));
}

// The process's peak resident memory so far, in MiB.
long peak_mib() {
  rusage usage{};
  ::getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss / 1024;
}

TEST_F(HostileFiles, CountsBeyondTheFileAreRefusedBeforeAllocating) {
  const long peak_before = peak_mib();
  // A PLY header claiming 4 billion vertices and a binary STL claiming 2 billion triangles, in files of bytes.
  write_file(dir_ / "huge.ply",
             "ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\nproperty float x\n"
             "property float y\nproperty float z\nelement face 1\nproperty list uchar int "
             "vertex_indices\nend_header\n" +
                 std::string(64, '\0'));
  EXPECT_NE(problem(dir_ / "huge.ply"), "");
  std::string stl(84 + 50, '\0');
  const std::uint32_t claimed = 2'000'000'000u;
  std::memcpy(stl.data() + 80, &claimed, 4);
  write_file(dir_ / "huge.stl", stl);
  EXPECT_NE(problem(dir_ / "huge.stl"), "");
  // An accessor whose count reaches past its buffer.
  std::string gltf = triangle_gltf("outside.bin");
  gltf.replace(gltf.find("\"count\":3"), 9, "\"count\":300000000");
  write_file(dir_ / "accessor.gltf", gltf);
  EXPECT_NE(problem(dir_ / "accessor.gltf"), "");
  // An accessor offset, and a buffer view, reaching past the 36 bytes of the buffer.
  std::string offset = triangle_gltf("outside.bin");
  offset.replace(offset.find("\"count\":3"), 9, "\"byteOffset\":4000000000,\"count\":3");
  write_file(dir_ / "offset.gltf", offset);
  EXPECT_NE(problem(dir_ / "offset.gltf", LoadOptions{.allow_external_files = true}), "");
  std::string view = triangle_gltf("outside.bin");
  view.replace(view.find("\"byteLength\":36}]"), 17, "\"byteLength\":36,\"byteOffset\":30}]");
  write_file(dir_ / "view.gltf", view);
  EXPECT_NE(problem(dir_ / "view.gltf", LoadOptions{.allow_external_files = true}), "");
  EXPECT_EQ(problem(dir_ / "accessor.gltf", LoadOptions{.allow_external_files = true}),
            "POSITION: accessor of 300000000 elements does not fit in its buffer view");
  // Refused from the sizes alone: gigabytes claimed, a few megabytes used.
  EXPECT_LT(peak_mib() - peak_before, 64) << "peak memory grew from " << peak_before << " MiB to " << peak_mib();
}

TEST_F(HostileFiles, NodeCyclesAndDeepChainsEnd) {
  std::string cycle = triangle_gltf("outside.bin");
  cycle.replace(cycle.find(R"("nodes":[{"mesh":0}])"), 20, R"("nodes":[{"mesh":0,"children":[1]},{"children":[0]}])");
  write_file(dir_ / "cycle.gltf", cycle);
  EXPECT_EQ(problem(dir_ / "cycle.gltf"), "node 0 is its own ancestor");

  // 100,000 nodes, each the child of the one before, the last placing the mesh.
  std::string nodes = R"("nodes":[)";
  constexpr int kDepth = 100000;
  for (int k = 0; k < kDepth; ++k)
    nodes += k + 1 < kDepth ? R"({"children":[)" + std::to_string(k + 1) + "]}," : std::string(R"({"mesh":0}])");
  std::string chain = triangle_gltf("outside.bin");
  chain.replace(chain.find(R"("nodes":[{"mesh":0}])"), 20, nodes);
  write_file(dir_ / "chain.gltf", chain);
  const auto start = std::chrono::steady_clock::now();
  EXPECT_EQ(problem(dir_ / "chain.gltf"), "the node hierarchy is more than 64 levels deep (at node 65)");
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(20));
}

TEST_F(HostileFiles, TriangleAndTextureLimits) {
  write_file(dir_ / "quad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n");
  EXPECT_EQ(problem(dir_ / "quad.obj", LoadOptions{.max_triangles = 2}), "");
  EXPECT_EQ(problem(dir_ / "quad.obj", LoadOptions{.max_triangles = 1}),
            "places 2 triangles, more than the limit of 1 (LoadOptions::max_triangles)");
  // A face names the setting its own way (the CLI by its flag, Python by its keyword).
  spell_settings([](std::string_view name) { return "<" + std::string(name) + ">"; });
  EXPECT_EQ(problem(dir_ / "quad.obj", LoadOptions{.max_triangles = 1}),
            "places 2 triangles, more than the limit of 1 (<max_triangles>)");
  spell_settings(nullptr);
  EXPECT_EQ(setting("max_triangles"), "LoadOptions::max_triangles");

  // A 64x64 texture under a limit of 32 a side: the material is drawn untextured, with a warning.
  write_png(dir_ / "big.png", 64, 64, std::vector<std::uint8_t>(64 * 64 * 4, 200));
  write_file(dir_ / "big.mtl", "newmtl m\nKd 1 1 1\nmap_Kd big.png\n");
  write_file(dir_ / "big.obj",
             "mtllib big.mtl\nusemtl m\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\n"
             "f 1/1 2/2 3/3\n");
  EXPECT_EQ(load_model(dir_ / "big.obj").materials.at(0).diffuse_texture, (dir_ / "big.png").string());
  WarningCapture warnings;
  EXPECT_EQ(load_model(dir_ / "big.obj", LoadOptions{.max_texture_size = 32}).materials.at(0).diffuse_texture, "");
  ASSERT_EQ(warnings.messages().size(), 1u);
  EXPECT_NE(warnings.messages()[0].find("is 64x64 texels, over the limit of 32 a side (LoadOptions::max_texture_size)"),
            std::string::npos)
      << warnings.messages()[0];
}

}  // namespace
}  // namespace facet::hostile_files_tests
