// test_assimp_loader.cpp - the Assimp fallback: one real file of each of six formats, refusals, whole folders.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "facet/error.hpp"
#include "facet/model_io.hpp"
#include "support/load_problem.hpp"
#include "support/scratch_dir.hpp"

namespace facet::assimp_loader_tests {
namespace {

namespace fs = std::filesystem;
const fs::path kModels = "/usr/share/assimp/models";

TEST(AssimpLoader, OneFileOfEachOfSixFormatsLoads) {
  const std::pair<const char*, std::size_t> files[] = {
      {"FBX/box.fbx", 12},  {"Collada/duck.dae", 4212},      {"3DS/fels.3ds", 0},
      {"OFF/Cube.off", 12}, {"X3D/ComputerKeyboard.x3d", 0}, {"3MF/box.3mf", 12}};
  for (const auto& [file, triangles] : files) {
    const Mesh m = load_model(kModels / file);
    EXPECT_GT(m.triangle_count(), 0u) << file;
    if (triangles) {
      EXPECT_EQ(m.triangle_count(), triangles) << file;
    }
  }
}

TEST(AssimpLoader, MaterialsCarryTheirColoursAndTexturePaths) {
  const Mesh duck = load_model(kModels / "Collada/duck.dae");
  ASSERT_FALSE(duck.materials.empty());
  EXPECT_EQ(duck.face_materials.size(), duck.triangle_count());
  bool textured = false;
  for (const Material& m : duck.materials)
    textured = textured || fs::path(m.diffuse_texture) == kModels / "Collada/duckCM.tga";
  EXPECT_TRUE(textured);
  EXPECT_EQ(duck.uvs.size(), duck.vertex_count());
}

TEST(AssimpLoader, BrokenFilesAreRefusedNamingThePath) {
  const fs::path dir = test::scratch_dir("assimp");
  std::ofstream(dir / "broken.off") << "OFF\n3 1 0\n0 0 0\n1 0 0\n";
  std::ofstream(dir / "garbage.fbx") << "this is not an FBX file at all\n";
  for (const fs::path& p : {kModels / "OFF/invalid.off", dir / "broken.off", dir / "garbage.fbx"})
    EXPECT_FALSE(test::load_problem(p).empty()) << p;
}

// Assimp opens the parts a LightWave scene names through facet's confined files: one outside the model's folder is
// looked for by its file name beside the model (a one-triangle OFF there), and read where it is (the 12-triangle
// cube) only when external files are allowed. (A part found nowhere is not tried: Assimp's LWS reader leaks then.)
TEST(AssimpLoader, PartsOutsideTheFolderAreNotRead) {
  const fs::path dir = test::scratch_dir("assimp_parts");
  std::ifstream cube_file(kModels / "OFF/Cube.off", std::ios::binary);
  const std::string cube((std::istreambuf_iterator<char>(cube_file)), std::istreambuf_iterator<char>());
  ASSERT_FALSE(cube.empty());
  test::write_file(dir, "outside/cube.off", cube);
  test::write_file(dir, "model/cube.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  const auto scene = [](const std::string& part) {
    return "LWSC\n3\n\nFirstFrame 1\nLastFrame 60\nFrameStep 1\n\nLoadObjectLayer 1 " + part + "\nShowObject 6 2\n";
  };
  const fs::path climbs = test::write_file(dir, "model/climbs.lws", scene("../outside/cube.off"));
  const fs::path absolute = test::write_file(dir, "model/absolute.lws", scene((dir / "outside/cube.off").string()));
  for (const fs::path& model : {climbs, absolute}) {
    EXPECT_EQ(load_model(model).triangle_count(), 1u) << model;
    EXPECT_EQ(load_model(model, LoadOptions{.allow_external_files = true}).triangle_count(), 12u) << model;
  }
}

// Every file of these format folders either loads (validated, at least one triangle) or is refused cleanly.
TEST(AssimpLoader, WholeFoldersLoadOrThrowInputError) {
  int loaded = 0;
  for (const char* folder : {"FBX", "Collada", "3DS", "OFF", "X3D", "3MF"}) {
    for (const auto& entry : fs::directory_iterator(kModels / folder)) {
      if (!entry.is_regular_file()) continue;
      const std::string ext = entry.path().extension().string();
      if (ext == ".jpg" || ext == ".png" || ext == ".tga" || ext == ".txt" || ext == ".bmp" || ext == ".dds") continue;
      try {
        EXPECT_GT(load_model(entry.path()).triangle_count(), 0u) << entry.path();
        ++loaded;
      } catch (const InputError& e) {
        EXPECT_EQ(e.source(), entry.path().string());
      }
    }
  }
  EXPECT_GT(loaded, 30);
}

// Debian's collection of broken files: each is refused with a one-line error, or loads; none hangs or crashes.
TEST(AssimpLoader, TheInvalidFolderIsRefusedCleanly) {
  int refused = 0;
  for (const auto& entry : fs::directory_iterator(kModels / "invalid")) {
    try {
      EXPECT_GT(load_model(entry.path()).triangle_count(), 0u) << entry.path();
    } catch (const InputError& e) {
      EXPECT_EQ(e.source(), entry.path().string());
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
      ++refused;
    }
  }
  EXPECT_GE(refused, 13);
  EXPECT_NE(test::load_problem(kModels / "invalid/OutOfMemory.off").find("do not fit"), std::string::npos);
}

}  // namespace
}  // namespace facet::assimp_loader_tests
