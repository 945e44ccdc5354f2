// assimp_animation.cpp - an Assimp scene's node tree, bones and node animations, in the Model glTF's reader fills.
#include "job/io/assimp_animation.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <utility>

#include <glm/gtx/matrix_decompose.hpp>

#include "facet/error.hpp"
#include "job/io/loaders.hpp"

namespace facet {

namespace {

constexpr std::size_t kMostInfluences = 8;

// The keys of one of a channel's three tracks as a sampler: times in seconds, duplicated times dropped (Assimp's
// readers repeat a key at a segment's end); `get` gives a key's time in ticks and writes its value.
template <class Key, class Get>
AnimationSampler sampler_of(const Key* keys, unsigned count, double seconds_per_tick, std::size_t width, Get get) {
  AnimationSampler s;
  s.width = width;
  for (unsigned k = 0; k < count; ++k) {
    const float t = static_cast<float>(keys[k].mTime * seconds_per_tick);
    if (!s.times.empty() && t == s.times.back()) continue;
    s.times.push_back(t);
    get(keys[k], s.values);
  }
  return s;
}

// Throws InputError naming the node whose keys are malformed.
Animation animation_of(const aiAnimation& a, const std::map<std::string, std::uint32_t>& node_ids,
                       std::vector<ModelNode>& nodes, const std::string& source) {
  Animation out;
  out.name = a.mName.C_Str();
  // Assimp's times are in ticks; a file that gives no rate is read at Assimp's default, 25 a second.
  const double ticks = a.mTicksPerSecond > 0.0 && std::isfinite(a.mTicksPerSecond) ? a.mTicksPerSecond : 25.0;
  for (unsigned c = 0; c < a.mNumChannels; ++c) {
    const aiNodeAnim* channel = a.mChannels[c];
    if (!channel) continue;
    const auto found = node_ids.find(channel->mNodeName.C_Str());
    if (found == node_ids.end()) continue;  // a node Assimp's tree does not hold: nothing to move
    const std::uint32_t node = found->second;
    // A channel gives the node's whole transform as translation, rotation and scale: its own matrix becomes those.
    ModelNode& n = nodes[node];
    if (n.matrix) {
      glm::vec3 skew;
      glm::vec4 perspective;
      glm::decompose(*n.matrix, n.scale, n.rotation, n.translation, skew, perspective);
      n.matrix.reset();
    }
    const auto vec3 = [](const aiVectorKey& key, std::vector<float>& v) {
      v.insert(v.end(), {key.mValue.x, key.mValue.y, key.mValue.z});
    };
    const auto quat = [](const aiQuatKey& key, std::vector<float>& v) {
      v.insert(v.end(), {key.mValue.x, key.mValue.y, key.mValue.z, key.mValue.w});
    };
    const double seconds_per_tick = 1.0 / ticks;
    const std::pair<AnimatedProperty, AnimationSampler> tracks[] = {
        {AnimatedProperty::translation,
         sampler_of(channel->mPositionKeys, channel->mNumPositionKeys, seconds_per_tick, 3, vec3)},
        {AnimatedProperty::rotation,
         sampler_of(channel->mRotationKeys, channel->mNumRotationKeys, seconds_per_tick, 4, quat)},
        {AnimatedProperty::scale,
         sampler_of(channel->mScalingKeys, channel->mNumScalingKeys, seconds_per_tick, 3, vec3)}};
    for (const auto& [property, sampler] : tracks) {
      if (sampler.times.empty()) continue;  // the node keeps that part of its own transform
      validate(sampler, "node '" + printable(channel->mNodeName.C_Str()) + "'", source);
      out.channels.push_back({static_cast<std::uint32_t>(out.samplers.size()), node, property});
      out.samplers.push_back(sampler);
    }
  }
  return out;
}

}  // namespace

void read_assimp_motion(const aiScene& scene, const std::vector<const aiNode*>& walked,
                        const std::vector<std::int32_t>& parents, const std::vector<std::uint32_t>& slots, Model& out,
                        const std::string& source) {
  // The nodes in the walk's order (their ids), by name for bones and channels: the first of a name wins.
  std::map<std::string, std::uint32_t> node_ids;
  out.nodes.resize(walked.size());
  for (std::size_t i = 0; i < walked.size(); ++i) {
    out.nodes[i].name = walked[i]->mName.C_Str();
    out.nodes[i].parent = parents[i];
    const aiMatrix4x4& m = walked[i]->mTransformation;
    out.nodes[i].matrix =
        glm::mat4(m.a1, m.b1, m.c1, m.d1, m.a2, m.b2, m.c2, m.d2, m.a3, m.b3, m.c3, m.d3, m.a4, m.b4, m.c4, m.d4);
    node_ids.try_emplace(out.nodes[i].name, static_cast<std::uint32_t>(i));
  }

  // Bones: each skinned aiMesh a skin of its own, its vertices weighted to at most 8 bones (the heaviest).
  out.deformations.assign(out.meshes.size(), MeshDeformation{});
  std::vector<std::int32_t> skin_of_slot(out.meshes.size(), -1);
  for (unsigned index = 0; index < scene.mNumMeshes; ++index) {
    const aiMesh* mesh = scene.mMeshes[index];
    if (!mesh || mesh->mNumBones == 0 || slots[index] >= out.meshes.size()) continue;
    const std::uint32_t slot = slots[index];
    const std::size_t vertices = out.meshes[slot].vertex_count();
    Skin skin;
    skin.name = mesh->mName.C_Str();
    std::vector<std::vector<std::pair<float, std::uint16_t>>> influences(vertices);
    for (unsigned b = 0; b < mesh->mNumBones; ++b) {
      const aiBone* bone = mesh->mBones[b];
      if (!bone) continue;
      const auto node = node_ids.find(bone->mName.C_Str());
      if (node == node_ids.end())
        throw InputError(
            source, "mesh " + std::to_string(index) + "'s bone '" + printable(bone->mName.C_Str()) + "' names no node");
      if (skin.joints.size() > 0xFFFF)
        throw InputError(source, "mesh " + std::to_string(index) + " has over 65536 bones");
      const aiMatrix4x4& m = bone->mOffsetMatrix;
      const auto joint = static_cast<std::uint16_t>(skin.joints.size());
      skin.joints.push_back(node->second);
      skin.inverse_bind_matrices.push_back(
          glm::mat4(m.a1, m.b1, m.c1, m.d1, m.a2, m.b2, m.c2, m.d2, m.a3, m.b3, m.c3, m.d3, m.a4, m.b4, m.c4, m.d4));
      for (unsigned w = 0; w < bone->mNumWeights; ++w)
        if (bone->mWeights[w].mVertexId < vertices)
          influences[bone->mWeights[w].mVertexId].emplace_back(bone->mWeights[w].mWeight, joint);
    }
    MeshDeformation& d = out.deformations[slot];
    std::size_t most = 0;
    for (auto& list : influences) most = std::max(most, std::min(list.size(), kMostInfluences));
    d.influences = most <= 4 ? 4 : 8;
    d.joints.assign(vertices * d.influences, 0);
    d.weights.assign(vertices * d.influences, 0.0f);
    for (std::size_t v = 0; v < vertices; ++v) {
      auto& list = influences[v];
      std::sort(list.begin(), list.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
      for (std::size_t k = 0; k < std::min<std::size_t>(list.size(), d.influences); ++k) {
        d.weights[v * d.influences + k] = list[k].first;
        d.joints[v * d.influences + k] = list[k].second;
      }
    }
    normalise_skin_weights(d, "mesh " + std::to_string(index), source);
    skin_of_slot[slot] = static_cast<std::int32_t>(out.skins.size());
    out.skins.push_back(std::move(skin));
  }
  for (ModelInstance& instance : out.instances) instance.skin = skin_of_slot[instance.mesh];
  if (std::all_of(out.deformations.begin(), out.deformations.end(), [](const auto& d) { return d.empty(); }))
    out.deformations.clear();

  for (unsigned i = 0; i < scene.mNumAnimations; ++i) {
    if (!scene.mAnimations[i]) continue;
    const std::string what =
        "animation " + std::to_string(i) +
        (scene.mAnimations[i]->mName.length ? " '" + printable(scene.mAnimations[i]->mName.C_Str()) + "'" : "");
    try {
      out.animations.push_back(animation_of(*scene.mAnimations[i], node_ids, out.nodes, source));
    } catch (const InputError& e) {
      std::string problem = e.what();
      if (problem.starts_with(source + ": ")) problem.erase(0, source.size() + 2);
      warn(source, what + " is left out: " + problem);
    }
  }
}

}  // namespace facet
