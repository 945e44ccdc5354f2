// test_assimp_animation.cpp - Assimp's animated formats posed by facet against an oracle in Assimp's own maths.
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <gtest/gtest.h>
#include <assimp/Importer.hpp>

#include <filesystem>
#include <string>
#include <vector>

#include "facet/model.hpp"
#include "facet/model_io.hpp"
#include "facet/warnings.hpp"

namespace facet::assimp_animation_tests {
namespace {

namespace fs = std::filesystem;
const fs::path kCollada = "/usr/share/assimp/models/Collada";

// The oracle: the file imported by Assimp's C++ interface, its nodes moved by animation 0 at `seconds` with
// aiVector3D and aiQuaternion::Interpolate (Assimp's slerp), composed down the tree, and each placed mesh's
// vertices skinned by its bones (or placed by its node), in the tree's pre-order: the order facet places them.
class Oracle {
 public:
  explicit Oracle(const fs::path& path) {
    scene_ = importer_.ReadFile(path.string(), aiProcess_Triangulate | aiProcess_SortByPType |
                                                   aiProcess_ValidateDataStructure | aiProcess_FindInvalidData);
  }
  const aiScene* scene() const { return scene_; }

  std::vector<aiVector3D> posed(double seconds) const {
    std::vector<aiVector3D> out;
    walk(scene_->mRootNode, aiMatrix4x4(), seconds, out);
    return out;
  }

 private:
  const aiNodeAnim* channel_of(const aiNode* node) const {
    const aiAnimation* a = scene_->mAnimations[0];
    for (unsigned c = 0; c < a->mNumChannels; ++c)
      if (a->mChannels[c]->mNodeName == node->mName) return a->mChannels[c];
    return nullptr;
  }

  // Linear between the keys around the tick (the first or last key outside them).
  template <class Key, class Value, class Mix>
  static Value at(const Key* keys, unsigned count, double tick, Mix mix) {
    if (tick <= keys[0].mTime) return keys[0].mValue;
    for (unsigned k = 0; k + 1 < count; ++k)
      if (tick < keys[k + 1].mTime) {
        const float u = static_cast<float>((tick - keys[k].mTime) / (keys[k + 1].mTime - keys[k].mTime));
        return mix(keys[k].mValue, keys[k + 1].mValue, u);
      }
    return keys[count - 1].mValue;
  }

  aiMatrix4x4 local(const aiNode* node, double seconds) const {
    const aiNodeAnim* ch = channel_of(node);
    if (!ch) return node->mTransformation;
    const double ticks = scene_->mAnimations[0]->mTicksPerSecond > 0 ? scene_->mAnimations[0]->mTicksPerSecond : 25;
    const double tick = seconds * ticks;
    const auto lerp = [](const aiVector3D& a, const aiVector3D& b, float u) { return a + (b - a) * u; };
    const auto slerp = [](const aiQuaternion& a, const aiQuaternion& b, float u) {
      aiQuaternion q;
      aiQuaternion::Interpolate(q, a, b, u);
      return q.Normalize();
    };
    const aiVector3D t = at<aiVectorKey, aiVector3D>(ch->mPositionKeys, ch->mNumPositionKeys, tick, lerp);
    const aiQuaternion r = at<aiQuatKey, aiQuaternion>(ch->mRotationKeys, ch->mNumRotationKeys, tick, slerp);
    const aiVector3D s = at<aiVectorKey, aiVector3D>(ch->mScalingKeys, ch->mNumScalingKeys, tick, lerp);
    return aiMatrix4x4(s, r, t);
  }

  aiMatrix4x4 global(const aiNode* node, double seconds) const {
    return node->mParent ? global(node->mParent, seconds) * local(node, seconds) : local(node, seconds);
  }

  void walk(const aiNode* node, const aiMatrix4x4& parent, double seconds, std::vector<aiVector3D>& out) const {
    const aiMatrix4x4 world = parent * local(node, seconds);
    for (unsigned k = 0; k < node->mNumMeshes; ++k) {
      const aiMesh* mesh = scene_->mMeshes[node->mMeshes[k]];
      std::vector<aiVector3D> skinned(mesh->mNumVertices, aiVector3D(0, 0, 0));
      std::vector<float> total(mesh->mNumVertices, 0.0f);
      for (unsigned b = 0; b < mesh->mNumBones; ++b) {
        const aiBone* bone = mesh->mBones[b];
        const aiMatrix4x4 m = global(scene_->mRootNode->FindNode(bone->mName), seconds) * bone->mOffsetMatrix;
        for (unsigned w = 0; w < bone->mNumWeights; ++w) {
          const aiVertexWeight& vw = bone->mWeights[w];
          skinned[vw.mVertexId] += (m * mesh->mVertices[vw.mVertexId]) * vw.mWeight;
          total[vw.mVertexId] += vw.mWeight;
        }
      }
      for (unsigned v = 0; v < mesh->mNumVertices; ++v)
        out.push_back(total[v] > 0 ? skinned[v] / total[v] : world * mesh->mVertices[v]);
    }
    for (unsigned c = 0; c < node->mNumChildren; ++c) walk(node->mChildren[c], world, seconds, out);
  }

  Assimp::Importer importer_;
  const aiScene* scene_ = nullptr;
};

void expect_posed_as_the_oracle(const fs::path& path, std::initializer_list<double> times, bool skinned) {
  const Oracle oracle(path);
  ASSERT_NE(oracle.scene(), nullptr) << path;
  ASSERT_GT(oracle.scene()->mNumAnimations, 0u);
  const WarningCapture quiet;
  const Model model = read_model(path);
  ASSERT_EQ(model.animations.size(), oracle.scene()->mNumAnimations);
  EXPECT_EQ(!model.skins.empty(), skinned);
  double moved = 0.0;
  const std::vector<aiVector3D> rest = oracle.posed(times.begin()[0]);
  for (const double t : times) {
    const std::vector<aiVector3D> want = oracle.posed(t);
    const Mesh got = flatten(pose(model, 0, t, path.string()), path.string());
    ASSERT_EQ(got.vertex_count(), want.size()) << path;
    for (std::size_t v = 0; v < want.size(); ++v) {
      const glm::vec3 w(want[v].x, want[v].y, want[v].z);
      EXPECT_NEAR(glm::length(got.positions[v] - w), 0.0f, 1e-3f * std::max(1.0f, glm::length(w)))
          << path.filename() << " t " << t << " vertex " << v;
      moved += (want[v] - rest[v]).Length();
    }
  }
  EXPECT_GT(moved, 1.0) << "the animation moves the model: the comparison is not of still poses";
}

TEST(AssimpAnimation, ASkinnedColladaBoxBendsAsAssimpsOwnMathsBendIt) {
  expect_posed_as_the_oracle(kCollada / "box_nested_animation.dae", {0.0, 0.3, 0.8, 1.25, 1.6}, true);
}

TEST(AssimpAnimation, ColladaNodesTurnAsAssimpsOwnMathsTurnThem) {
  expect_posed_as_the_oracle(kCollada / "anims_with_full_rotations_between_keys.DAE", {0.0, 1.1, 4.5, 9.7}, false);
}

}  // namespace
}  // namespace facet::assimp_animation_tests
