// pose.cpp - a model at a moment: its clip's channels set the nodes, morph targets and skins move the vertices.
#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>

#include <glm/gtc/matrix_transform.hpp>

#include "core/thread_pool.hpp"
#include "facet/error.hpp"
#include "facet/model.hpp"

namespace facet {

using detail::ThreadPool;

namespace {

glm::mat4 local_from_node(const ModelNode& node) {
  if (node.matrix) return *node.matrix;
  return glm::translate(glm::mat4(1.0f), node.translation) * glm::mat4_cast(node.rotation) *
         glm::scale(glm::mat4(1.0f), node.scale);
}

std::size_t property_width(AnimatedProperty property) {
  switch (property) {
    case AnimatedProperty::translation:
    case AnimatedProperty::scale: return 3;
    case AnimatedProperty::rotation: return 4;
    case AnimatedProperty::weights: return 0;  // the morph target count
  }
  return 0;
}

// Sets every node a channel of the clip drives to its value at `seconds`. Channels on a node given by a matrix are
// skipped (glTF forbids them; the reader warns).
void apply_clip(const Animation& clip, float seconds, std::vector<ModelNode>& nodes, const std::string& source) {
  // The channels' messages are made only when something is wrong: this runs every frame of a clip.
  const auto named = [&](const char* part, std::size_t i) {
    return "animation '" + clip.name + "', " + part + " " + std::to_string(i);
  };
  for (std::size_t i = 0; i < clip.samplers.size(); ++i) validate(clip.samplers[i], named("sampler", i), source);
  float values[4];
  std::vector<float> weights;
  for (std::size_t c = 0; c < clip.channels.size(); ++c) {
    const AnimationChannel& channel = clip.channels[c];
    const auto what = [&] { return named("channel", c); };
    if (channel.sampler >= clip.samplers.size())
      throw InputError(source, what() + " uses sampler " + std::to_string(channel.sampler) + ", which does not exist");
    if (channel.node >= nodes.size())
      throw InputError(source, what() + " drives node " + std::to_string(channel.node) + ", which does not exist");
    const AnimationSampler& sampler = clip.samplers[channel.sampler];
    ModelNode& node = nodes[channel.node];
    const std::size_t width = property_width(channel.property);
    if (width != 0 && sampler.width != width)
      throw InputError(
          source, what() + " has keys of " + std::to_string(sampler.width) + " values, not " + std::to_string(width));
    if (node.matrix) continue;
    switch (channel.property) {
      case AnimatedProperty::translation:
        sample(sampler, seconds, false, values);
        node.translation = glm::vec3(values[0], values[1], values[2]);
        break;
      case AnimatedProperty::scale:
        sample(sampler, seconds, false, values);
        node.scale = glm::vec3(values[0], values[1], values[2]);
        break;
      case AnimatedProperty::rotation:
        sample(sampler, seconds, true, values);
        node.rotation = glm::normalize(glm::quat(values[3], values[0], values[1], values[2]));
        break;
      case AnimatedProperty::weights:
        weights.resize(sampler.width);
        sample(sampler, seconds, false, weights);
        node.weights = weights;
        break;
    }
  }
}

// The mesh's vertices moved by its morph targets at these weights: positions and tangents by the weighted sums of
// the targets' offsets, normals too, renormalised.
void morph(Mesh& mesh, const MeshDeformation& d, std::span<const float> weights) {
  for (std::size_t t = 0; t < d.morph_targets.size(); ++t) {
    const float w = weights[t];
    if (w == 0.0f) continue;
    const MorphTarget& target = d.morph_targets[t];
    for (std::size_t v = 0; v < target.positions.size(); ++v) mesh.positions[v] += w * target.positions[v];
    if (!mesh.normals.empty())
      for (std::size_t v = 0; v < target.normals.size(); ++v) mesh.normals[v] += w * target.normals[v];
    if (!mesh.tangents.empty())
      for (std::size_t v = 0; v < target.tangents.size(); ++v)
        mesh.tangents[v] += glm::vec4(w * target.tangents[v], 0.0f);
  }
  for (glm::vec3& n : mesh.normals) {
    const float length = glm::length(n);
    n = length > 0.0f ? n / length : glm::vec3(0, 0, 1);
  }
  for (glm::vec4& t : mesh.tangents) {
    const float length = glm::length(glm::vec3(t));
    if (length > 0.0f) t = glm::vec4(glm::vec3(t) / length, t.w);
  }
}

// The mesh's vertices skinned into world space: each moved by the blend of its joints' matrices (joint's world
// transform times its inverse bind matrix) by its weights; a vertex of no weight by `unskinned`, its node's world
// transform. Normals and tangents are moved by the same blend and renormalised, as three.js and glTF viewers do.
void skin(Mesh& mesh, const MeshDeformation& d, std::span<const glm::mat4> joint_matrices, const glm::mat4& unskinned,
          ThreadPool* pool) {
  const std::size_t n = mesh.positions.size(), k = d.influences;
  constexpr std::size_t kPart = 16384;
  const auto part = [&](std::size_t index, int) {
    const std::size_t end = std::min(n, (index + 1) * kPart);
    for (std::size_t v = index * kPart; v < end; ++v) {
      glm::mat4 m(0.0f);
      float total = 0.0f;
      for (std::size_t i = 0; i < k; ++i) {
        const float w = d.weights[v * k + i];
        if (w == 0.0f) continue;
        m += w * joint_matrices[d.joints[v * k + i]];
        total += w;
      }
      if (total == 0.0f) m = unskinned;
      mesh.positions[v] = glm::vec3(m * glm::vec4(mesh.positions[v], 1.0f));
      const glm::mat3 linear(m);
      if (!mesh.normals.empty()) {
        const glm::vec3 normal = linear * mesh.normals[v];
        const float length = glm::length(normal);
        mesh.normals[v] = length > 0.0f ? normal / length : glm::vec3(0, 0, 1);
      }
      if (!mesh.tangents.empty()) {
        const glm::vec3 tangent = linear * glm::vec3(mesh.tangents[v]);
        const float length = glm::length(tangent);
        mesh.tangents[v] = length > 0.0f ? glm::vec4(tangent / length, mesh.tangents[v].w) : glm::vec4(0.0f);
      }
    }
  };
  const std::size_t parts = (n + kPart - 1) / kPart;
  if (pool) pool->parallel_for(parts, [&](std::size_t index, int thread) { part(index, thread); });
  else
    for (std::size_t p = 0; p < parts; ++p) part(p, 0);
}

// Throws unless every array of the deformation fits the mesh it moves.
void check_deformation(const Mesh& mesh, const MeshDeformation& d, std::uint32_t index, const std::string& source) {
  const std::size_t n = mesh.vertex_count();
  const std::string what = "mesh " + std::to_string(index);
  if (!d.morph_targets.empty() && d.default_weights.size() != d.morph_targets.size())
    throw InputError(source, what + " has " + std::to_string(d.default_weights.size()) + " default weights for " +
                                 std::to_string(d.morph_targets.size()) + " morph targets");
  for (std::size_t t = 0; t < d.morph_targets.size(); ++t)
    for (const std::size_t size :
         {d.morph_targets[t].positions.size(), d.morph_targets[t].normals.size(), d.morph_targets[t].tangents.size()})
      if (size != 0 && size != n)
        throw InputError(source, what + "'s morph target " + std::to_string(t) + " has " + std::to_string(size) +
                                     " entries for " + std::to_string(n) + " vertices");
  if (d.joints.size() != n * d.influences || d.weights.size() != n * d.influences)
    throw InputError(source, what + " has " + std::to_string(d.joints.size()) + " joints and " +
                                 std::to_string(d.weights.size()) + " weights for " + std::to_string(n) +
                                 " vertices of " + std::to_string(d.influences) + " influences");
}

}  // namespace

glm::mat4 rigid_camera_pose(const glm::mat4& world_from_node) {
  glm::mat4 pose = world_from_node;
  for (int axis = 0; axis < 3; ++axis) {
    const float length = glm::length(glm::vec3(pose[axis]));
    pose[axis] = length > 0.0f ? pose[axis] / length : glm::vec4(0.0f);
  }
  return pose;
}

bool place_light(Light& light, const glm::mat4& world_from_node) {
  const glm::vec3 position(world_from_node[3]);
  const glm::vec3 forward = -glm::vec3(world_from_node[2]);  // the node's -Z
  const auto finite = [](glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); };
  if (!finite(position) || !finite(forward) || glm::dot(forward, forward) == 0.0f) return false;
  if (light.kind == Light::Kind::directional) {
    light.vector = -glm::normalize(forward);
  } else {
    light.vector = position;
    light.spot_direction = glm::normalize(forward);
  }
  return true;
}

std::vector<glm::mat4> world_from_nodes(const std::vector<ModelNode>& nodes, const std::string& source) {
  std::vector<glm::mat4> world(nodes.size());
  std::vector<char> state(nodes.size(), 0);  // 0 not yet, 1 on the path being resolved, 2 done
  std::vector<std::size_t> path;
  for (std::size_t start = 0; start < nodes.size(); ++start) {
    // Up the parents to a resolved node or a root, then down again composing the transforms.
    for (std::size_t at = start; state[at] != 2;) {
      if (state[at] == 1) throw InputError(source, "node " + std::to_string(at) + " is its own ancestor");
      state[at] = 1;
      path.push_back(at);
      const std::int32_t parent = nodes[at].parent;
      if (parent < 0) break;
      if (static_cast<std::size_t>(parent) >= nodes.size())
        throw InputError(source,
                         "node " + std::to_string(at) + "'s parent " + std::to_string(parent) + " does not exist");
      at = static_cast<std::size_t>(parent);
    }
    for (auto it = path.rbegin(); it != path.rend(); ++it) {
      const std::int32_t parent = nodes[*it].parent;
      world[*it] =
          (parent < 0 ? glm::mat4(1.0f) : world[static_cast<std::size_t>(parent)]) * local_from_node(nodes[*it]);
      state[*it] = 2;
    }
    path.clear();
  }
  return world;
}

struct Poser::Kept {
  int threads = 1;
  std::optional<ThreadPool> pool;  // made when a mesh first needs it
  Model out;
  std::vector<std::uint32_t> slot_of_mesh;  // per input mesh nothing moves: its index in out.meshes, or kNoSlot
};

Poser::Poser(int threads) : kept_(std::make_unique<Kept>()) {
  kept_->threads = threads == 0 ? static_cast<int>(std::max(1u, std::thread::hardware_concurrency())) : threads;
}
Poser::~Poser() = default;
Poser::Poser(Poser&&) noexcept = default;
Poser& Poser::operator=(Poser&&) noexcept = default;

Model pose(const Model& model, std::optional<std::size_t> animation, double seconds, const std::string& source,
           int threads) {
  Poser poser(threads);
  return std::move(poser(model, animation, seconds, source));
}

Model at_rest(Model model, const std::string& source, int threads) {
  if (model.deformations.empty()) return model;
  return pose(model, std::nullopt, 0.0, source, threads);
}

Model& Poser::operator()(const Model& model, std::optional<std::size_t> animation, double seconds,
                         const std::string& source) {
  if (!std::isfinite(seconds)) throw std::invalid_argument("time: must be a finite number of seconds");
  if (!model.deformations.empty() && model.deformations.size() != model.meshes.size())
    throw InputError(source, std::to_string(model.deformations.size()) + " mesh deformations for " +
                                 std::to_string(model.meshes.size()) + " meshes");
  for (std::size_t m = 0; m < model.deformations.size(); ++m)
    check_deformation(model.meshes[m], model.deformations[m], static_cast<std::uint32_t>(m), source);
  std::vector<ModelNode> nodes = model.nodes;
  if (animation) apply_clip(model.animations.at(*animation), static_cast<float>(seconds), nodes, source);
  const std::vector<glm::mat4> world = world_from_nodes(nodes, source);

  // The meshes are copied into the last frame's, whose vectors keep their memory.
  Model& out = kept_->out;
  out.cameras = model.cameras;
  out.lights = model.lights;
  out.camera_nodes = model.camera_nodes;
  out.light_nodes = model.light_nodes;
  // Cameras and lights follow their nodes.
  const auto node_of = [&](const std::vector<std::int32_t>& list, std::size_t i) -> const glm::mat4* {
    if (i >= list.size() || list[i] < 0) return nullptr;
    if (static_cast<std::size_t>(list[i]) >= nodes.size())
      throw InputError(source,
                       "a camera or light is placed by node " + std::to_string(list[i]) + ", which does not exist");
    return &world[static_cast<std::size_t>(list[i])];
  };
  for (std::size_t c = 0; c < out.cameras.size(); ++c)
    if (const glm::mat4* w = node_of(model.camera_nodes, c)) out.cameras[c].world_from_camera = rigid_camera_pose(*w);
  for (std::size_t l = 0; l < out.lights.size(); ++l)
    if (const glm::mat4* w = node_of(model.light_nodes, l)) place_light(out.lights[l], *w);
  out.skins = model.skins;
  out.animations.clear();
  out.deformations.clear();
  out.instances.clear();
  std::size_t meshes = 0;
  const auto next_mesh = [&](const Mesh& from) -> Mesh& {
    if (meshes == out.meshes.size()) out.meshes.emplace_back();
    Mesh& mesh = out.meshes[meshes++];
    mesh = from;
    return mesh;
  };
  constexpr std::uint32_t kNoSlot = 0xFFFFFFFFu;
  std::vector<std::uint32_t>& slot_of_mesh = kept_->slot_of_mesh;
  slot_of_mesh.assign(model.meshes.size(), kNoSlot);
  for (const ModelInstance& instance : model.instances) {
    if (instance.mesh >= model.meshes.size())
      throw InputError(source, "instance " + std::to_string(instance.id) + " places mesh " +
                                   std::to_string(instance.mesh) + ", which does not exist");
    if (instance.node >= 0 && static_cast<std::size_t>(instance.node) >= nodes.size())
      throw InputError(source, "instance " + std::to_string(instance.id) + " is placed by node " +
                                   std::to_string(instance.node) + ", which does not exist");
    if (instance.skin >= 0 && static_cast<std::size_t>(instance.skin) >= model.skins.size())
      throw InputError(source, "instance " + std::to_string(instance.id) + " uses skin " +
                                   std::to_string(instance.skin) + ", which does not exist");
    ModelInstance placed = instance;
    if (instance.node >= 0) placed.world_from_object = world[static_cast<std::size_t>(instance.node)];
    const Mesh& mesh = model.meshes[instance.mesh];
    static const MeshDeformation kNone;
    const MeshDeformation& d = model.deformations.empty() ? kNone : model.deformations[instance.mesh];
    const std::span<const float> weights =
        instance.node >= 0 && !nodes[static_cast<std::size_t>(instance.node)].weights.empty()
            ? std::span<const float>(nodes[static_cast<std::size_t>(instance.node)].weights)
            : std::span<const float>(d.default_weights);
    const bool morphed =
        !d.morph_targets.empty() && std::any_of(weights.begin(), weights.end(), [](float w) { return w != 0.0f; });
    const bool skinned = instance.skin >= 0 && d.influences > 0;
    if (!morphed && !skinned) {
      std::uint32_t& slot = slot_of_mesh[instance.mesh];
      if (slot == kNoSlot) {
        slot = static_cast<std::uint32_t>(meshes);
        next_mesh(mesh);
      }
      placed.mesh = slot;
      out.instances.push_back(placed);
      continue;
    }
    placed.mesh = static_cast<std::uint32_t>(meshes);
    Mesh& moved = next_mesh(mesh);
    if (morphed) {
      if (weights.size() != d.morph_targets.size())
        throw InputError(source, "instance " + std::to_string(instance.id) + " has " + std::to_string(weights.size()) +
                                     " morph weights for " + std::to_string(d.morph_targets.size()) + " targets");
      morph(moved, d, weights);
    }
    if (skinned) {
      const Skin& s = model.skins[static_cast<std::size_t>(instance.skin)];
      std::vector<glm::mat4> joint_matrices(s.joints.size());
      for (std::size_t j = 0; j < s.joints.size(); ++j) {
        if (s.joints[j] >= nodes.size())
          throw InputError(source, "skin " + std::to_string(instance.skin) + "'s joint " + std::to_string(j) +
                                       " is node " + std::to_string(s.joints[j]) + ", which does not exist");
        joint_matrices[j] =
            world[s.joints[j]] * (j < s.inverse_bind_matrices.size() ? s.inverse_bind_matrices[j] : glm::mat4(1.0f));
      }
      for (std::size_t i = 0; i < d.joints.size(); ++i)
        if (d.joints[i] >= s.joints.size() && d.weights[i] != 0.0f)
          throw InputError(source, "vertex " + std::to_string(i / d.influences) + " is weighted to joint " +
                                       std::to_string(d.joints[i]) + ", but skin " + std::to_string(instance.skin) +
                                       " has " + std::to_string(s.joints.size()) + " joints");
      std::optional<ThreadPool>& pool = kept_->pool;
      if (!pool && kept_->threads > 1 && moved.vertex_count() >= 32768) pool.emplace(kept_->threads);
      skin(moved, d, joint_matrices, placed.world_from_object, pool ? &*pool : nullptr);
      placed.world_from_object = glm::mat4(1.0f);
    }
    out.instances.push_back(placed);
  }
  out.meshes.resize(meshes);
  out.nodes = std::move(nodes);
  return out;
}

}  // namespace facet
