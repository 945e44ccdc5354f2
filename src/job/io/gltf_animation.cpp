// gltf_animation.cpp - a glTF file's node tree, skins, animations, and its meshes' skinning weights and morph targets.
#include "job/io/gltf_animation.hpp"

#include <algorithm>
#include <cmath>
#include <glm/gtc/type_ptr.hpp>
#include <string>

#include "job/io/loaders.hpp"

namespace facet {

std::vector<ModelNode> read_nodes(const Reader& reader) {
  const auto& nodes = reader.model.nodes;
  std::vector<ModelNode> out(nodes.size());
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const tinygltf::Node& n = nodes[i];
    ModelNode& node = out[i];
    node.name = n.name;
    if (n.matrix.size() == 16) {
      glm::mat4 m;
      for (int k = 0; k < 16; ++k) glm::value_ptr(m)[k] = static_cast<float>(n.matrix[static_cast<std::size_t>(k)]);
      node.matrix = m;
    }
    if (n.translation.size() == 3)
      node.translation = glm::vec3(static_cast<float>(n.translation[0]), static_cast<float>(n.translation[1]),
                                   static_cast<float>(n.translation[2]));
    if (n.rotation.size() == 4)
      node.rotation = glm::normalize(glm::quat(static_cast<float>(n.rotation[3]), static_cast<float>(n.rotation[0]),
                                               static_cast<float>(n.rotation[1]), static_cast<float>(n.rotation[2])));
    if (n.scale.size() == 3)
      node.scale =
          glm::vec3(static_cast<float>(n.scale[0]), static_cast<float>(n.scale[1]), static_cast<float>(n.scale[2]));
    for (double w : n.weights) node.weights.push_back(static_cast<float>(w));
    for (int child : n.children) {
      if (child < 0 || static_cast<std::size_t>(child) >= nodes.size())
        reader.fail("node " + std::to_string(i) + "'s child " + std::to_string(child) + " does not exist");
      if (out[static_cast<std::size_t>(child)].parent >= 0 || static_cast<std::size_t>(child) == i)
        reader.fail("node " + std::to_string(child) + " has more than one parent");
      out[static_cast<std::size_t>(child)].parent = static_cast<std::int32_t>(i);
    }
  }
  world_from_nodes(out, reader.source);  // refuses a node that is its own ancestor
  return out;
}

std::vector<Skin> read_skins(const Reader& reader) {
  std::vector<Skin> out;
  for (std::size_t s = 0; s < reader.model.skins.size(); ++s) {
    const tinygltf::Skin& skin = reader.model.skins[s];
    const std::string what = "skin " + std::to_string(s);
    Skin made;
    made.name = skin.name;
    for (int joint : skin.joints) {
      if (joint < 0 || static_cast<std::size_t>(joint) >= reader.model.nodes.size())
        reader.fail(what + "'s joint node " + std::to_string(joint) + " does not exist");
      made.joints.push_back(static_cast<std::uint32_t>(joint));
    }
    made.inverse_bind_matrices.assign(made.joints.size(), glm::mat4(1.0f));
    if (skin.inverseBindMatrices >= 0) {
      const std::vector<float> values = reader.floats(skin.inverseBindMatrices, 16, "inverseBindMatrices");
      if (values.size() < 16 * made.joints.size())
        reader.fail(what + " has " + std::to_string(values.size() / 16) + " inverse bind matrices for " +
                    std::to_string(made.joints.size()) + " joints");
      if (!std::all_of(values.begin(), values.end(), [](float v) { return std::isfinite(v); }))
        reader.fail(what + "'s inverse bind matrices are not all finite");
      for (std::size_t j = 0; j < made.joints.size(); ++j)
        made.inverse_bind_matrices[j] = glm::make_mat4(values.data() + 16 * j);
    }
    out.push_back(std::move(made));
  }
  return out;
}

namespace {

// The morph target count of the mesh a node places (0 for none): what its weights channel must give.
std::size_t targets_of_node(const tinygltf::Model& model, int node) {
  const int mesh = model.nodes[static_cast<std::size_t>(node)].mesh;
  if (mesh < 0 || static_cast<std::size_t>(mesh) >= model.meshes.size()) return 0;
  const auto& primitives = model.meshes[static_cast<std::size_t>(mesh)].primitives;
  return primitives.empty() ? 0 : primitives.front().targets.size();
}

// Throws InputError with the problem of the first malformed part, named within the animation ("sampler 2: ...").
Animation read_animation(const Reader& reader, const tinygltf::Animation& a, const std::string& what,
                         bool& warned_matrix) {
  Animation out;
  out.name = a.name;
  for (std::size_t i = 0; i < a.samplers.size(); ++i) {
    const tinygltf::AnimationSampler& s = a.samplers[i];
    const std::string sampler = "sampler " + std::to_string(i);
    AnimationSampler made;
    if (s.interpolation == "LINEAR" || s.interpolation.empty()) made.interpolation = Interpolation::linear;
    else if (s.interpolation == "STEP") made.interpolation = Interpolation::step;
    else if (s.interpolation == "CUBICSPLINE") made.interpolation = Interpolation::cubic_spline;
    else reader.fail(sampler + " has the unknown interpolation '" + printable(s.interpolation) + "'");
    made.times = reader.floats(s.input, 1, "animation input");
    if (s.output < 0 || static_cast<std::size_t>(s.output) >= reader.model.accessors.size())
      reader.fail(sampler + "'s output accessor " + std::to_string(s.output) + " does not exist");
    const int type = reader.model.accessors[static_cast<std::size_t>(s.output)].type;
    const int components = type == TINYGLTF_TYPE_VEC3 ? 3 : type == TINYGLTF_TYPE_VEC4 ? 4 : 1;
    made.values = reader.floats(s.output, components, "animation output");
    // A weights sampler's keys hold one value per morph target: its width is what the keys leave.
    const std::size_t keys = std::max<std::size_t>(made.times.size(), 1);
    const std::size_t per_key = made.interpolation == Interpolation::cubic_spline ? 3 : 1;
    made.width = components == 1 ? made.values.size() / (keys * per_key) : static_cast<std::size_t>(components);
    validate(made, sampler, reader.source);
    out.samplers.push_back(std::move(made));
  }
  for (std::size_t c = 0; c < a.channels.size(); ++c) {
    const tinygltf::AnimationChannel& ch = a.channels[c];
    const std::string channel = "channel " + std::to_string(c);
    if (ch.target_node < 0) continue;  // a target given another way (KHR_animation_pointer): not read
    if (static_cast<std::size_t>(ch.target_node) >= reader.model.nodes.size())
      reader.fail(channel + " drives node " + std::to_string(ch.target_node) + ", which does not exist");
    if (ch.sampler < 0 || static_cast<std::size_t>(ch.sampler) >= out.samplers.size())
      reader.fail(channel + " uses sampler " + std::to_string(ch.sampler) + ", which does not exist");
    AnimationChannel made{static_cast<std::uint32_t>(ch.sampler), static_cast<std::uint32_t>(ch.target_node)};
    std::size_t width = 0;
    if (ch.target_path == "translation") {
      made.property = AnimatedProperty::translation, width = 3;
    } else if (ch.target_path == "rotation") {
      made.property = AnimatedProperty::rotation, width = 4;
    } else if (ch.target_path == "scale") {
      made.property = AnimatedProperty::scale, width = 3;
    } else if (ch.target_path == "weights") {
      made.property = AnimatedProperty::weights, width = targets_of_node(reader.model, ch.target_node);
    } else {
      continue;  // "pointer" and paths of extensions
    }
    const std::size_t given = out.samplers[made.sampler].width;
    if (given != width)
      reader.fail(channel + " (" + ch.target_path + ") has keys of " + std::to_string(given) + " values, not " +
                  std::to_string(width));
    if (reader.model.nodes[static_cast<std::size_t>(ch.target_node)].matrix.size() == 16) {
      if (!warned_matrix)
        warn(reader.source, what + ", " + channel + " drives node " + std::to_string(ch.target_node) +
                                ", which is given by a matrix; such channels are not played");
      warned_matrix = true;
      continue;
    }
    out.channels.push_back(made);
  }
  return out;
}

}  // namespace

std::vector<Animation> read_animations(const Reader& reader) {
  std::vector<Animation> out;
  bool warned_matrix = false;
  for (std::size_t i = 0; i < reader.model.animations.size(); ++i) {
    const tinygltf::Animation& a = reader.model.animations[i];
    const std::string what = "animation " + std::to_string(i) + (a.name.empty() ? "" : " '" + printable(a.name) + "'");
    try {
      out.push_back(read_animation(reader, a, what, warned_matrix));
    } catch (const InputError& e) {
      std::string problem = e.what();
      if (problem.starts_with(reader.source + ": ")) problem.erase(0, reader.source.size() + 2);
      warn(reader.source, what + " is left out: " + problem);
    }
  }
  return out;
}

void DeformationReader::start(int index) {
  mesh_ = index;
  vertices_ = influences_ = 0;
  joints_.clear();
  weights_.clear();
  targets_.clear();
  any_normals_ = any_tangents_ = false;
}

void DeformationReader::primitive(const tinygltf::Primitive& p, std::size_t count, bool decoded) {
  const std::size_t base = vertices_;
  vertices_ += count;
  joints_.resize(vertices_ * kMostInfluences, 0);
  weights_.resize(vertices_ * kMostInfluences, 0.0f);
  const auto attribute = [&](const std::string& name) {
    const auto it = p.attributes.find(name);
    return decoded || it == p.attributes.end() ? -1 : it->second;
  };
  for (std::size_t set = 0; set < kMostInfluences / 4; ++set) {
    const std::string joints_name = "JOINTS_" + std::to_string(set), weights_name = "WEIGHTS_" + std::to_string(set);
    const int joints = attribute(joints_name), weights = attribute(weights_name);
    if (joints < 0 || weights < 0) break;
    const std::vector<std::uint32_t> j = reader_.unsigned_integers(joints, 4, joints_name.c_str());
    const std::vector<float> w = reader_.floats(weights, 4, weights_name.c_str());
    if (j.size() != 4 * count || w.size() != 4 * count)
      reader_.fail(joints_name + " and " + weights_name + " have " + std::to_string(j.size() / 4) + " and " +
                   std::to_string(w.size() / 4) + " elements but POSITION has " + std::to_string(count));
    for (std::size_t v = 0; v < count; ++v)
      for (std::size_t c = 0; c < 4; ++c) {
        const std::size_t at = (base + v) * kMostInfluences + 4 * set + c;
        if (j[4 * v + c] > 0xFFFF) reader_.fail(joints_name + " names joint " + std::to_string(j[4 * v + c]));
        joints_[at] = static_cast<std::uint16_t>(j[4 * v + c]);
        weights_[at] = w[4 * v + c];
      }
    influences_ = std::max(influences_, 4 * (set + 1));
  }
  const std::size_t targets = decoded ? 0 : p.targets.size();
  if (targets_.empty() && targets > 0 && base == 0) targets_.resize(targets);
  if (targets != targets_.size())
    reader_.fail("mesh " + std::to_string(mesh_) + "'s primitives have " + std::to_string(targets_.size()) + " and " +
                 std::to_string(targets) + " morph targets");
  for (std::size_t t = 0; t < targets; ++t) {
    MorphTarget& target = targets_[t];
    const auto offsets = [&](const char* name, std::vector<glm::vec3>& into, bool* any) {
      const auto it = p.targets[t].find(name);
      into.resize(base, glm::vec3(0.0f));
      if (it == p.targets[t].end()) return into.resize(vertices_, glm::vec3(0.0f));
      const std::vector<float> d = reader_.floats(it->second, 3, name);
      if (d.size() != 3 * count)
        reader_.fail(std::string("morph target ") + name + " has " + std::to_string(d.size() / 3) +
                     " elements but POSITION has " + std::to_string(count));
      for (std::size_t v = 0; v < count; ++v) into.emplace_back(d[3 * v], d[3 * v + 1], d[3 * v + 2]);
      if (any) *any = true;
    };
    offsets("POSITION", target.positions, nullptr);
    offsets("NORMAL", target.normals, &any_normals_);
    offsets("TANGENT", target.tangents, &any_tangents_);
  }
}

MeshDeformation DeformationReader::finish() {
  MeshDeformation out;
  const tinygltf::Mesh& mesh = reader_.model.meshes[static_cast<std::size_t>(mesh_)];
  if (!targets_.empty()) {
    for (MorphTarget& t : targets_) {
      if (!any_normals_) t.normals.clear();
      if (!any_tangents_) t.tangents.clear();
    }
    out.morph_targets = std::move(targets_);
    out.default_weights.assign(out.morph_targets.size(), 0.0f);
    if (!mesh.weights.empty() && mesh.weights.size() != out.default_weights.size())
      reader_.fail("mesh " + std::to_string(mesh_) + " has " + std::to_string(mesh.weights.size()) + " weights for " +
                   std::to_string(out.default_weights.size()) + " morph targets");
    for (std::size_t t = 0; t < mesh.weights.size(); ++t) out.default_weights[t] = static_cast<float>(mesh.weights[t]);
  }
  if (influences_ > 0) {
    out.influences = static_cast<std::uint32_t>(influences_);
    out.joints.resize(vertices_ * influences_);
    out.weights.resize(vertices_ * influences_);
    for (std::size_t v = 0; v < vertices_; ++v)
      for (std::size_t c = 0; c < influences_; ++c) {
        out.joints[v * influences_ + c] = joints_[v * kMostInfluences + c];
        out.weights[v * influences_ + c] = weights_[v * kMostInfluences + c];
      }
    normalise_skin_weights(out, "mesh " + std::to_string(mesh_), reader_.source);
  }
  return out;
}

void normalise_skin_weights(MeshDeformation& d, const std::string& what, const std::string& source) {
  const std::size_t k = d.influences, vertices = k ? d.weights.size() / k : 0;
  std::size_t bad_weights = 0, unsummed = 0;
  for (std::size_t v = 0; v < vertices; ++v) {
    float* w = &d.weights[v * k];
    float total = 0.0f;
    bool bad = false;
    for (std::size_t c = 0; c < k; ++c) {
      if (!std::isfinite(w[c]) || w[c] < 0.0f) w[c] = 0.0f, bad = true;
      total += w[c];
    }
    bad_weights += bad;
    if (total > 0.0f && std::abs(total - 1.0f) > 1e-3f) ++unsummed;
    for (std::size_t c = 0; c < k; ++c) w[c] = total > 0.0f ? w[c] / total : 0.0f;
  }
  if (bad_weights)
    warn(source,
         what + ": " + std::to_string(bad_weights) + " vertices have negative or non-finite skin weights, taken as 0");
  if (unsummed)
    warn(source,
         what + ": " + std::to_string(unsummed) + " vertices' skin weights do not sum to 1; they are normalised");
}

}  // namespace facet
