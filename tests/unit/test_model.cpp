// test_model.cpp - read_model's meshes and instances for every format, and flatten() against Assimp's own.
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <gtest/gtest.h>

#include <assimp/Importer.hpp>
#include <filesystem>
#include <fstream>
#include <glm/gtc/matrix_transform.hpp>
#include <string>

#include "facet/error.hpp"
#include "facet/model.hpp"
#include "facet/model_io.hpp"
#include "support/scratch_dir.hpp"

namespace facet::model_tests {
namespace {

namespace fs = std::filesystem;
const fs::path kModels = "/usr/share/assimp/models";

// One triangle (0,0,0) (1,0,0) (0,1,0) with normals +Z, placed by node 1 (moved by +2 in x, under node 0, which
// moves by +10 in y), by node 2 (mirrored in x) and by node 3 (identity); node 4 places nothing.
constexpr const char* kInstancedGltf =
    R"({"asset":{"version":"2.0"},"buffers":[{"byteLength":72,"uri":"data:application/octet-stream;base64,)"
    R"(AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAAAAAAAAAAAAIA/AAAAAAAAAAAAAIA/AAAAAAAAAAAAAIA/"}],)"
    R"("bufferViews":[{"buffer":0,"byteLength":36},{"buffer":0,"byteOffset":36,"byteLength":36}],)"
    R"("accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]},)"
    R"({"bufferView":1,"componentType":5126,"count":3,"type":"VEC3"}],)"
    R"("materials":[{"name":"red","pbrMetallicRoughness":{"baseColorFactor":[1,0,0,1]}}],)"
    R"("meshes":[{"primitives":[{"attributes":{"POSITION":0,"NORMAL":1},"material":0}]}],)"
    R"("nodes":[{"translation":[0,10,0],"children":[1]},{"mesh":0,"translation":[2,0,0]},)"
    R"({"mesh":0,"scale":[-1,1,1]},{"mesh":0},{}],"scenes":[{"nodes":[0,2,3,4]}],"scene":0})";

TEST(Model, GltfNodesPlaceOneMeshThreeTimes) {
  const fs::path dir = test::scratch_dir("model");
  std::ofstream(dir / "instanced.gltf") << kInstancedGltf;
  const Model model = read_model(dir / "instanced.gltf");
  ASSERT_EQ(model.meshes.size(), 1u);
  EXPECT_EQ(model.meshes[0].triangle_count(), 1u);
  EXPECT_TRUE(model.meshes[0].instance_ids.empty());
  EXPECT_EQ(model.meshes[0].positions[1], glm::vec3(1, 0, 0));  // object space, as the file has it
  ASSERT_EQ(model.instances.size(), 3u);
  EXPECT_EQ(model.instances[0].id, 1u);
  EXPECT_EQ(model.instances[1].id, 2u);
  EXPECT_EQ(model.instances[2].id, 3u);
  for (const ModelInstance& i : model.instances) EXPECT_EQ(i.mesh, 0u);
  EXPECT_EQ(model.instances[0].world_from_object, glm::translate(glm::mat4(1.0f), glm::vec3(2, 10, 0)));
  EXPECT_EQ(model.instances[1].world_from_object, glm::scale(glm::mat4(1.0f), glm::vec3(-1, 1, 1)));
  EXPECT_EQ(model.instances[2].world_from_object, glm::mat4(1.0f));
}

TEST(Model, FlattenPlacesEveryInstanceFrontFacing) {
  const fs::path dir = test::scratch_dir("model");
  std::ofstream(dir / "instanced.gltf") << kInstancedGltf;
  const Mesh flat = load_model(dir / "instanced.gltf");
  ASSERT_EQ(flat.triangle_count(), 3u);
  ASSERT_EQ(flat.materials.size(), 1u);  // one material, however many meshes and instances use it
  EXPECT_EQ(flat.face_materials, (std::vector<std::int32_t>{0, 0, 0}));
  EXPECT_EQ(flat.instance_ids, (std::vector<std::uint32_t>{1, 2, 3}));
  EXPECT_EQ(flat.face_ids, (std::vector<std::uint32_t>{0, 0, 0}));
  EXPECT_EQ(flat.positions[1], glm::vec3(3, 10, 0));
  EXPECT_EQ(flat.positions[4], glm::vec3(-1, 0, 0));
  for (std::size_t t = 0; t < 3; ++t) {
    const glm::vec3 a = flat.positions[flat.indices[3 * t]], b = flat.positions[flat.indices[3 * t + 1]];
    const glm::vec3 c = flat.positions[flat.indices[3 * t + 2]];
    // Counter-clockwise seen from +Z, and the normal (reflected for the mirrored instance) still points there.
    EXPECT_GT(glm::cross(b - a, c - a).z, 0.0f) << "triangle " << t;
    EXPECT_EQ(flat.normals[flat.indices[3 * t]], glm::vec3(0, 0, 1)) << "triangle " << t;
  }
}

TEST(Model, SingleMeshFormatsAreOneInstanceAtTheOrigin) {
  for (const char* file : {"OBJ/box.obj", "PLY/cube.ply", "STL/Spider_ascii.stl"}) {
    const Model model = read_model(kModels / file);
    ASSERT_EQ(model.meshes.size(), 1u) << file;
    ASSERT_EQ(model.instances.size(), 1u) << file;
    EXPECT_EQ(model.instances[0].world_from_object, glm::mat4(1.0f)) << file;
    EXPECT_EQ(model.instances[0].id, 0u) << file;
    const Mesh flat = load_model(kModels / file);
    EXPECT_EQ(flat.positions, model.meshes[0].positions) << file;
    EXPECT_EQ(flat.indices, model.meshes[0].indices) << file;
    EXPECT_TRUE(flat.instance_ids.empty()) << file;
  }
}

TEST(Model, FlattenRefusesAModelWithNothingPlaced) {
  Model model;
  model.meshes.push_back(Mesh{});
  EXPECT_THROW(flatten(model, "empty"), InputError);
  model.instances.push_back(ModelInstance{.mesh = 3});
  EXPECT_THROW(flatten(model, "dangling"), InputError);
}

// Area of every triangle, summed: the same for any order of triangles and vertices.
double total_area(const std::vector<glm::vec3>& p, const std::vector<std::uint32_t>& indices) {
  double area = 0;
  for (std::size_t t = 0; t + 2 < indices.size(); t += 3)
    area += 0.5 * glm::length(glm::cross(p[indices[t + 1]] - p[indices[t]], p[indices[t + 2]] - p[indices[t]]));
  return area;
}

// Assimp's node trees, walked by facet and flattened, give what Assimp's own pre-transform gives: the same
// triangles, bounds and area, on files whose nodes nest, instance one mesh twice, and scale and rotate.
TEST(Model, AssimpNodesFlattenAsAssimpPreTransformsThem) {
  for (const char* file :
       {"Collada/teapot_instancenodes.DAE", "Collada/teapots.DAE", "Collada/COLLADA.dae", "Collada/Cinema4D.dae",
        "Collada/duck.dae", "FBX/box.fbx", "3DS/fels.3ds", "X3D/ComputerKeyboard.x3d"}) {
    const fs::path path = kModels / file;
    Assimp::Importer importer;
    importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
    const aiScene* scene = importer.ReadFile(
        path.string(), aiProcess_Triangulate | aiProcess_SortByPType | aiProcess_PreTransformVertices);
    ASSERT_TRUE(scene) << file;
    std::vector<glm::vec3> positions;
    std::vector<std::uint32_t> indices;
    for (unsigned i = 0; i < scene->mNumMeshes; ++i) {
      const aiMesh& m = *scene->mMeshes[i];
      const auto base = static_cast<std::uint32_t>(positions.size());
      for (unsigned v = 0; v < m.mNumVertices; ++v)
        positions.emplace_back(m.mVertices[v].x, m.mVertices[v].y, m.mVertices[v].z);
      for (unsigned f = 0; f < m.mNumFaces; ++f)
        if (m.mFaces[f].mNumIndices == 3)
          for (unsigned k = 0; k < 3; ++k) indices.push_back(base + m.mFaces[f].mIndices[k]);
    }
    const Mesh flat = load_model(path);
    ASSERT_EQ(flat.triangle_count(), indices.size() / 3) << file;
    Mesh reference;
    reference.positions = positions;
    const Bounds want = bounds(reference), got = bounds(flat);
    const float tolerance = 1e-4f * want.radius();
    for (int axis = 0; axis < 3; ++axis) {
      EXPECT_NEAR(got.min[axis], want.min[axis], tolerance) << file << " axis " << axis;
      EXPECT_NEAR(got.max[axis], want.max[axis], tolerance) << file << " axis " << axis;
    }
    const double area = total_area(positions, indices);
    EXPECT_NEAR(total_area(flat.positions, flat.indices), area, 1e-4 * area) << file;
  }
  const Model instanced = read_model(kModels / "Collada/teapot_instancenodes.DAE");
  EXPECT_EQ(instanced.meshes.size(), 1u);
  EXPECT_EQ(instanced.instances.size(), 2u);
}

}  // namespace
}  // namespace facet::model_tests
