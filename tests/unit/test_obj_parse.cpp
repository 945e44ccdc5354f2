// test_obj_parse.cpp - facet's OBJ parser reads every file as tinyobjloader does: real models and odd spellings.
#include <gtest/gtest.h>
#include <tiny_obj_loader.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include "facet/error.hpp"
#include "job/io/obj_parse.hpp"

namespace facet::obj_parse_tests {
namespace {

namespace fs = std::filesystem;

// tinyobjloader parses numbers digit by digit in double precision, facet rounds them correctly to float: the two
// may differ in the last place.
bool same_real(float a, float b) {
  if (a == b || (std::isnan(a) && std::isnan(b))) return true;
  return std::nextafter(a, b) == b;
}

void expect_same_reals(const std::vector<float>& facet, const std::vector<float>& tinyobj, const char* what,
                       const std::string& name) {
  ASSERT_EQ(facet.size(), tinyobj.size()) << name << ": " << what;
  std::size_t differing = 0;
  for (std::size_t i = 0; i < facet.size(); ++i) {
    if (!same_real(facet[i], tinyobj[i]))
      ADD_FAILURE() << name << ": " << what << "[" << i << "] " << facet[i] << " vs " << tinyobj[i];
    differing += facet[i] != tinyobj[i];
  }
  EXPECT_LE(differing, facet.size() / 100 + 1) << name << ": " << what << " differ in the last place too often";
}

// Parses `text` both ways (materials read from `folder` by tinyobjloader's reader in both) and compares.
void expect_same_as_tinyobj(const std::string& text, const fs::path& folder, const std::string& name) {
  tinyobj::MaterialFileReader tiny_reader(folder.string() + "/");
  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  std::vector<tinyobj::material_t> tiny_materials;
  std::string warnings, errors;
  std::istringstream in(text);
  const bool tiny_ok = tinyobj::LoadObj(&attrib, &shapes, &tiny_materials, &warnings, &errors, &in, &tiny_reader,
                                        /*triangulate=*/false, /*default_vcols_fallback=*/false);

  std::vector<tinyobj::material_t> materials;
  tinyobj::MaterialFileReader reader(folder.string() + "/");
  const ObjMaterialReader read = [&](const std::string& file, std::map<std::string, int>& names) {
    std::string w, e;
    return reader(file, &materials, &names, &w, &e);
  };
  ObjData obj;
  try {
    obj = parse_obj(text, read, name);
  } catch (const InputError& e) {
    EXPECT_FALSE(tiny_ok) << name << ": facet refused (" << e.what() << "), tinyobjloader read it";
    return;
  }
  ASSERT_TRUE(tiny_ok) << name << ": facet read it, tinyobjloader refused: " << errors;

  expect_same_reals(obj.positions, attrib.vertices, "positions", name);
  expect_same_reals(obj.normals, attrib.normals, "normals", name);
  expect_same_reals(obj.uvs, attrib.texcoords, "uvs", name);
  expect_same_reals(obj.colors, attrib.colors, "colors", name);
  EXPECT_EQ(materials.size(), tiny_materials.size()) << name;

  // tinyobjloader keeps a polygon's corner count in 8 bits; facet's are compared modulo 256.
  std::vector<ObjCorner> corners;
  std::vector<unsigned> face_sizes, tiny_face_sizes;
  std::vector<std::int32_t> face_materials;
  for (const tinyobj::shape_t& shape : shapes) {
    for (const tinyobj::index_t& i : shape.mesh.indices)
      corners.push_back({i.vertex_index, i.texcoord_index, i.normal_index});
    tiny_face_sizes.insert(tiny_face_sizes.end(), shape.mesh.num_face_vertices.begin(),
                           shape.mesh.num_face_vertices.end());
    face_materials.insert(face_materials.end(), shape.mesh.material_ids.begin(), shape.mesh.material_ids.end());
  }
  for (std::size_t f = 0; f < obj.face_ends.size(); ++f)
    face_sizes.push_back((obj.face_ends[f] - (f == 0 ? 0u : obj.face_ends[f - 1])) % 256u);
  ASSERT_EQ(obj.corners.size(), corners.size()) << name;
  for (std::size_t k = 0; k < corners.size(); ++k) {
    const ObjCorner a = obj.corners[k], b = corners[k];
    ASSERT_TRUE(a.v == b.v && a.vt == b.vt && a.vn == b.vn)
        << name << ": corner " << k << " (" << a.v << "/" << a.vt << "/" << a.vn << ") vs (" << b.v << "/" << b.vt
        << "/" << b.vn << ")";
  }
  EXPECT_EQ(face_sizes, tiny_face_sizes) << name;
  EXPECT_EQ(obj.face_materials, face_materials) << name;
  std::size_t degenerate = 0;
  for (std::size_t at = warnings.find("Degenerated face"); at != std::string::npos;
       at = warnings.find("Degenerated face", at + 1))
    ++degenerate;
  EXPECT_EQ(obj.dropped_faces, degenerate) << name;
}

std::string read_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(ObjParse, EveryAssimpTestModelReadsAsTinyobjloaderReadsIt) {
  std::size_t files = 0;
  for (const char* root : {"/usr/share/assimp/models", "/usr/share/assimp/models-nonbsd"}) {
    if (!fs::exists(root)) continue;
    for (const auto& entry : fs::recursive_directory_iterator(root)) {
      std::string extension = entry.path().extension().string();
      for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
      if (extension != ".obj") continue;
      SCOPED_TRACE(entry.path().string());
      expect_same_as_tinyobj(read_text(entry.path()), entry.path().parent_path(), entry.path().filename().string());
      ++files;
    }
  }
  if (files == 0) GTEST_SKIP() << "assimp-testmodels not installed";
  EXPECT_GE(files, 20u);
}

TEST(ObjParse, OddSpellingsReadAsTinyobjloaderReadsThem) {
  const fs::path none = fs::temp_directory_path() / "facet_obj_parse_no_such_folder";
  const std::string four = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 1\nvn 0 0 1\n";
  static constexpr char kWithNul[] = "v 1 2 3\nv 4 5 6\nv 7 8 9\nf 1 2 3\0junk\nf 1 3 2\n";
  const std::vector<std::string> texts = {
      four + "f 1 2 3 4\n",
      four + "f 1/1 2/2 3/1\nf 1//1 2//1 3//1\nf 1/1/1 2/2/1 3/2/1\n",
      four + "f -4 -3 -2\nf -4/-2/-1 -3/-1/-1 -1/-2/-1\n",
      "v 1 2 3\r\nv 4 5 6\r\nv 7 8 9\r\nf 1 2 3\r\n",                   // CRLF
      "v 1 2 3\rv 4 5 6\rv 7 8 9\rf 1 2 3",                               // lone CR, no final break
      "v +1.5e2 -.25 3.\nv 1e-3 1E+3 -0\nv 0x10 1.5x 7e\nf 1 2 3\n",      // number spellings
      "v 1e999 -1e999 1e-999\nv 1 2 3\nv 4 5 6\nf 1 2 3\n",               // out of float's range
      "  \t v 1 2 3\n\tv\t4 5 6\nv  7  8  9  \nf\t1   2\t3 \n# c\n\n",    // blanks and comments
      "v 1 2 3 0.5 0.25 1\nv 4 5 6 1 0 0\nv 7 8 9 0 1 0\nf 1 2 3\n",      // colours
      "v 1 2 3 0.5 0.25\nv 4 5 6 1 0 0\nv 7 8 9 0 1 0\nf 1 2 3\n",        // an incomplete colour
      "v 1 2\nv 3\nv\nvt 0.5\nvn 1\nf 1 2 3\n",                           // missing components
      four + "f 1 2\nf 3\nf 1 2 3\n",                                      // degenerate faces
      four + "f 1x 2/ 3/ 4\nf 1/1/ 2/2/ 3/1/\n",                          // trailing junk after indices
      four + "f 99999999999 1 2\nf 1 2 -99999999999999999999\n",          // indices beyond int
      four + "usemtl a\nf 1 2 3\ng x\nf 1 3 4\no y\nusemtl\nf 2 3 4\n",  // unknown materials, groups
      four + "mtllib none.mtl\nusemtl a\nf 1 2 3\n",                      // a missing library
      four + "f 0 1 2\n",                                                  // index 0
      four + "f 1 2 a\n",                                                  // not a number
      four + "l 1 2\np 3\nf 1 2 3\n",                                      // lines and points
      four + "l 1 0\n",                                                    // a line's index 0
      std::string(kWithNul, sizeof kWithNul - 1),                        // a NUL
  };
  for (std::size_t i = 0; i < texts.size(); ++i) {
    SCOPED_TRACE("text " + std::to_string(i));
    expect_same_as_tinyobj(texts[i], none, "text " + std::to_string(i) + ".obj");
  }
}

TEST(ObjParse, ProblemsNameTheLine) {
  const auto problem = [](const std::string& text) {
    try {
      parse_obj(text, {}, "m.obj");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no problem");
  };
  EXPECT_EQ(problem("v 0 0 0\n\r\nf 1 0 1\n"), "m.obj: malformed 'f' element on line 3 (an index is 0 or not a number)");
  EXPECT_EQ(problem("v 0 0 0\rp x\n"), "m.obj: malformed 'p' element on line 2 (an index is 0 or not a number)");
  EXPECT_EQ(problem("v 0 0 0\nv 0 -NaN 0\n"), "m.obj: non-finite vertex position on line 2");
  EXPECT_EQ(problem("vn nan nan nan\nvt inf inf\n"), "no problem");  // only positions must be finite
}

}  // namespace
}  // namespace facet::obj_parse_tests
