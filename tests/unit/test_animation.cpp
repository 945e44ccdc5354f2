// test_animation.cpp - samplers and pose(): keys, slerps and splines, a two-bone arm, morphing, broken models.
#include <gtest/gtest.h>

#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <limits>
#include <string>
#include <vector>

#include "facet/animation.hpp"
#include "facet/error.hpp"
#include "facet/model.hpp"
#include "facet/primitives.hpp"

namespace facet::animation_tests {
namespace {

constexpr float kPi = 3.14159265358979f;

float sample1(const AnimationSampler& s, float t) {
  float v = 0.0f;
  sample(s, t, false, std::span<float>(&v, 1));
  return v;
}

TEST(AnimationSampler, LinearAndStepHoldTheEndKeysOutsideTheClip) {
  AnimationSampler s{{1.0f, 2.0f, 4.0f}, {0.0f, 10.0f, 30.0f}, 1, Interpolation::linear};
  EXPECT_FLOAT_EQ(sample1(s, 0.5f), 0.0f);
  EXPECT_FLOAT_EQ(sample1(s, 1.5f), 5.0f);
  EXPECT_FLOAT_EQ(sample1(s, 3.0f), 20.0f);
  EXPECT_FLOAT_EQ(sample1(s, 4.0f), 30.0f);
  EXPECT_FLOAT_EQ(sample1(s, 9.0f), 30.0f);
  s.interpolation = Interpolation::step;
  EXPECT_FLOAT_EQ(sample1(s, 1.5f), 0.0f);
  EXPECT_FLOAT_EQ(sample1(s, 2.0f), 10.0f);
  EXPECT_FLOAT_EQ(sample1(s, 3.9f), 10.0f);
}

// The Hermite segment written as the Bezier curve it is: control points p0, p0 + m0 dt / 3, p1 - m1 dt / 3, p1.
float bezier(float p0, float m0, float p1, float m1, float dt, float u) {
  const float c1 = p0 + m0 * dt / 3.0f, c2 = p1 - m1 * dt / 3.0f, v = 1.0f - u;
  return v * v * v * p0 + 3 * v * v * u * c1 + 3 * v * u * u * c2 + u * u * u * p1;
}

TEST(AnimationSampler, CubicSplineIsTheHermiteCurveOfGltf) {
  // Keys at 0.5 s and 2.5 s: (in-tangent, value, out-tangent) each.
  const AnimationSampler s{{0.5f, 2.5f}, {9.0f, 1.0f, 3.0f, -2.0f, 4.0f, 7.0f}, 1, Interpolation::cubic_spline};
  for (const float u : {0.0f, 0.1f, 0.25f, 0.5f, 0.8f, 1.0f})
    EXPECT_NEAR(sample1(s, 0.5f + 2.0f * u), bezier(1.0f, 3.0f, 4.0f, -2.0f, 2.0f, u), 1e-5f) << u;
  EXPECT_FLOAT_EQ(sample1(s, 0.0f), 1.0f);  // values, not tangents, before and after
  EXPECT_FLOAT_EQ(sample1(s, 3.0f), 4.0f);
}

TEST(AnimationSampler, RotationsSlerpAlongTheShorterArc) {
  // From no turn to 90 degrees about z, the second key given as the negated quaternion (the same rotation).
  const float h = std::sqrt(0.5f);
  const AnimationSampler s{{0.0f, 1.0f}, {0, 0, 0, 1, 0, 0, -h, -h}, 4, Interpolation::linear};
  for (const float u : {0.25f, 0.5f, 0.9f}) {
    float q[4];
    sample(s, u, true, q);
    const glm::vec3 x = glm::quat(q[3], q[0], q[1], q[2]) * glm::vec3(1, 0, 0);
    const float angle = u * kPi / 2;
    EXPECT_NEAR(x.x, std::cos(angle), 1e-5f) << u;
    EXPECT_NEAR(x.y, std::sin(angle), 1e-5f) << u;
    EXPECT_NEAR(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3], 1.0f, 1e-5f);
  }
}

std::string sampler_problem(const AnimationSampler& s) {
  try {
    validate(s, "animation 'Walk', sampler 2", "arm.glb");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(AnimationSampler, BrokenKeysAreRefusedByName) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const AnimationSampler good{{0.0f, 1.0f}, {0.0f, 1.0f}, 1, Interpolation::linear};
  EXPECT_EQ(sampler_problem(good), "");
  AnimationSampler s = good;
  s.times = {1.0f, 1.0f};
  EXPECT_NE(sampler_problem(s).find("arm.glb: animation 'Walk', sampler 2: key times do not increase"),
            std::string::npos)
      << sampler_problem(s);
  s.times = {0.0f, nan};
  EXPECT_NE(sampler_problem(s).find("not a finite number"), std::string::npos);
  s = good;
  s.values[1] = std::numeric_limits<float>::infinity();
  EXPECT_NE(sampler_problem(s).find("value 1 is not a finite number"), std::string::npos);
  s = good;
  s.interpolation = Interpolation::cubic_spline;  // needs three values a key
  EXPECT_NE(sampler_problem(s).find("has 2 values for 2 keys of 3"), std::string::npos);
  s = good;
  s.times.clear();
  EXPECT_NE(sampler_problem(s).find("has no keys"), std::string::npos);
}

TEST(AnimationSampler, AnimationsAreFoundByNameThenIndex) {
  std::vector<Animation> clips(3);
  clips[0].name = "Walk";
  clips[1].name = "2";
  EXPECT_EQ(find_animation(clips, "Walk"), 0u);
  EXPECT_EQ(find_animation(clips, "2"), 1u);  // a name wins over an index
  EXPECT_EQ(find_animation(clips, "0"), 0u);
  EXPECT_EQ(find_animation(clips, "3"), std::nullopt);
  EXPECT_EQ(find_animation(clips, "Run"), std::nullopt);
  EXPECT_EQ(find_animation(clips, ""), std::nullopt);
  EXPECT_EQ(find_animation(clips, "1x"), std::nullopt);
}

// An arm along +x from 0 to 2 (a strip of quads, its vertices at x = 0, 0.5, ..., 2, y = 0 and 0.1): the upper arm's
// vertices follow joint 0 (node 1, at the origin), the forearm's joint 1 (node 2, at x = 1), the elbow's both
// equally. The mesh's own node (0) is moved away: a skinned mesh ignores it. Animation 0 turns the elbow from 0 to
// 90 degrees about z over 1 s.
Model two_bone_arm() {
  Model model;
  Mesh arm;
  MeshDeformation d;
  d.influences = 4;
  for (int i = 0; i <= 4; ++i)
    for (const float y : {0.0f, 0.1f}) {
      const float x = 0.5f * static_cast<float>(i);
      arm.positions.emplace_back(x, y, 0.0f);
      const float forearm = x < 1.0f ? 0.0f : x > 1.0f ? 1.0f : 0.5f;
      d.joints.insert(d.joints.end(), {0, 1, 0, 0});
      d.weights.insert(d.weights.end(), {1.0f - forearm, forearm, 0.0f, 0.0f});
    }
  for (std::uint32_t i = 0; i < 4; ++i)
    arm.indices.insert(arm.indices.end(), {2 * i, 2 * i + 2, 2 * i + 3, 2 * i, 2 * i + 3, 2 * i + 1});
  model.meshes.push_back(arm);
  model.deformations.push_back(d);
  model.nodes.resize(3);
  model.nodes[0].translation = glm::vec3(5, 0, 0);
  model.nodes[2].parent = 1;
  model.nodes[2].translation = glm::vec3(1, 0, 0);
  model.skins.push_back(Skin{"arm", {1, 2}, {glm::mat4(1.0f), glm::translate(glm::mat4(1.0f), glm::vec3(-1, 0, 0))}});
  ModelInstance instance;
  instance.node = 0;
  instance.skin = 0;
  instance.world_from_object = glm::translate(glm::mat4(1.0f), glm::vec3(5, 0, 0));
  model.instances.push_back(instance);
  const float h = std::sqrt(0.5f);
  Animation bend{"bend", {{{0.0f, 1.0f}, {0, 0, 0, 1, 0, 0, h, h}, 4, Interpolation::linear}}, {{0, 2}}};
  bend.channels[0].property = AnimatedProperty::rotation;
  model.animations.push_back(bend);
  return model;
}

// Where the elbow's turn by `angle` puts an arm vertex: the upper arm stays, the forearm turns about (1, 0, 0).
glm::vec3 bent(glm::vec3 p, float angle) {
  const float c = std::cos(angle), s = std::sin(angle);
  const glm::vec3 forearm(1.0f + c * (p.x - 1.0f) - s * p.y, s * (p.x - 1.0f) + c * p.y, p.z);
  const float w = p.x < 1.0f ? 0.0f : p.x > 1.0f ? 1.0f : 0.5f;
  return (1.0f - w) * p + w * forearm;
}

TEST(Pose, ATwoBoneArmBendsAtItsElbow) {
  const Model arm = two_bone_arm();
  for (const float t : {0.0f, 0.3f, 0.5f, 1.0f, 2.0f}) {
    const Model posed = pose(arm, 0, t, "arm");
    ASSERT_EQ(posed.instances.size(), 1u);
    EXPECT_EQ(posed.instances[0].world_from_object, glm::mat4(1.0f));  // skinned into world space
    const Mesh& mesh = posed.meshes[posed.instances[0].mesh];
    const float angle = std::min(t, 1.0f) * kPi / 2;
    for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
      const glm::vec3 want = bent(arm.meshes[0].positions[v], angle), got = mesh.positions[v];
      EXPECT_NEAR(glm::length(got - want), 0.0f, 1e-5f) << "t " << t << " vertex " << v;
    }
    EXPECT_TRUE(posed.deformations.empty());
    EXPECT_TRUE(posed.animations.empty());
  }
  // Unanimated, the skin still places the arm: at its bind pose, not at its node's x = 5.
  const Model rest = pose(arm, std::nullopt, 0.0, "arm");
  EXPECT_EQ(rest.meshes[0].positions, arm.meshes[0].positions);
}

TEST(Pose, ArmsSkinnedOnSeveralThreadsMatchOneThread) {
  Model arm = two_bone_arm();
  // 40,000 copies of the arm's vertices, one mesh: large enough to be skinned in parts.
  Mesh& mesh = arm.meshes[0];
  MeshDeformation& d = arm.deformations[0];
  const Mesh one = mesh;
  const MeshDeformation first = d;
  for (int copy = 1; copy < 4000; ++copy) {
    for (const glm::vec3& p : one.positions) mesh.positions.push_back(p + glm::vec3(0, 0, 0.001f * copy));
    d.joints.insert(d.joints.end(), first.joints.begin(), first.joints.end());
    d.weights.insert(d.weights.end(), first.weights.begin(), first.weights.end());
  }
  const Model single = pose(arm, 0, 0.7, "arm", 1), several = pose(arm, 0, 0.7, "arm", 3);
  EXPECT_EQ(single.meshes[0].positions, several.meshes[0].positions);
  for (std::size_t v = 0; v < mesh.positions.size(); v += 997)
    EXPECT_NEAR(glm::length(single.meshes[0].positions[v] - bent(mesh.positions[v], 0.7f * kPi / 2)), 0.0f, 1e-5f);
}

TEST(Pose, APoserGivesWhatPoseGivesFrameAfterFrame) {
  const Model arm = two_bone_arm();
  Model two = arm;  // the arm placed twice, the second time unskinned: two meshes out
  two.instances.push_back(ModelInstance{0, glm::mat4(1.0f), 1, 0, -1});
  Poser poser(2);
  for (const double t : {0.0, 0.4, 0.9, 0.4}) {
    for (const Model* model : std::vector<const Model*>{&arm, &two, &arm}) {
      const Model& kept = poser(*model, 0, t, "arm");
      const Model fresh = pose(*model, 0, t, "arm");
      ASSERT_EQ(kept.meshes.size(), fresh.meshes.size());
      ASSERT_EQ(kept.instances.size(), fresh.instances.size());
      for (std::size_t m = 0; m < kept.meshes.size(); ++m)
        EXPECT_EQ(kept.meshes[m].positions, fresh.meshes[m].positions);
      for (std::size_t i = 0; i < kept.instances.size(); ++i) {
        EXPECT_EQ(kept.instances[i].mesh, fresh.instances[i].mesh);
        EXPECT_EQ(kept.instances[i].world_from_object, fresh.instances[i].world_from_object);
      }
    }
  }
}

TEST(Pose, AMorphingCubeBlendsItsTargetsByTheNodesAnimatedWeights) {
  Model model;
  const Mesh cube = make_cube();
  MeshDeformation d;
  d.morph_targets.resize(2);
  for (const glm::vec3& p : cube.positions) {
    d.morph_targets[0].positions.emplace_back(p.x > 0.0f ? 1.0f : 0.0f, 0.0f, 0.0f);  // stretches along +x
    d.morph_targets[1].positions.emplace_back(0.0f, p.y > 0.0f ? 0.5f : 0.0f, 0.0f);  // raises its top
    d.morph_targets[1].normals.emplace_back(p.y > 0.0f ? 0.3f : 0.0f, 0.0f, 0.0f);    // and tilts the top's normals
  }
  d.default_weights = {0.5f, 0.0f};
  model.meshes.push_back(cube);
  model.deformations.push_back(d);
  model.nodes.resize(1);
  model.instances.push_back(ModelInstance{0, glm::mat4(1.0f), 0, 0, -1});
  Animation grow{"grow", {{{0.0f, 2.0f}, {0, 0, 1, 0.5f}, 2, Interpolation::linear}}, {{0, 0}}};
  grow.channels[0].property = AnimatedProperty::weights;
  model.animations.push_back(grow);
  const auto expect_blend = [&](const Mesh& got, float w0, float w1) {
    ASSERT_EQ(got.vertex_count(), cube.vertex_count());
    for (std::size_t v = 0; v < cube.vertex_count(); ++v) {
      const glm::vec3 want =
          cube.positions[v] + w0 * d.morph_targets[0].positions[v] + w1 * d.morph_targets[1].positions[v];
      EXPECT_NEAR(glm::length(got.positions[v] - want), 0.0f, 1e-6f) << v;
      const glm::vec3 normal = glm::normalize(cube.normals[v] + w1 * d.morph_targets[1].normals[v]);
      EXPECT_NEAR(glm::length(got.normals[v] - normal), 0.0f, 1e-6f) << v;
    }
  };
  // Unanimated: the mesh's default weights; at 1 s the animated (0.5, 0.25); past the end (1, 0.5).
  expect_blend(pose(model, std::nullopt, 0.0, "cube").meshes[0], 0.5f, 0.0f);
  expect_blend(pose(model, 0, 1.0, "cube").meshes[0], 0.5f, 0.25f);
  expect_blend(pose(model, 0, 7.0, "cube").meshes[0], 1.0f, 0.5f);
  // A node's own weights replace the mesh's defaults.
  model.nodes[0].weights = {0.0f, 1.0f};
  expect_blend(pose(model, std::nullopt, 0.0, "cube").meshes[0], 0.0f, 1.0f);
  model.nodes[0].weights = {1.0f};
  EXPECT_THROW(pose(model, std::nullopt, 0.0, "cube"), InputError);
}

TEST(Pose, ANodeOnACubicSplineCarriesItsChildren) {
  Model model;
  Mesh point;
  point.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  point.indices = {0, 1, 2};
  model.meshes.push_back(point);
  model.nodes.resize(2);
  model.nodes[1].parent = 0;
  model.nodes[1].scale = glm::vec3(2.0f);
  model.instances.push_back(ModelInstance{0, glm::mat4(1.0f), 1, 1, -1});
  // Node 0's translation: a spline from (0, 0, 0) to (3, 0, 6) over 2 s, tangents (1, 0, 0) out and (0, 0, 4) in.
  Animation move{
      "move",
      {{{0.0f, 2.0f}, {0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 4, 3, 0, 6, 0, 0, 0}, 3, Interpolation::cubic_spline}},
      {{0, 0}}};
  model.animations.push_back(move);
  for (const float t : {0.0f, 0.5f, 1.3f, 2.0f}) {
    const glm::mat4 world = pose(model, 0, t, "spline").instances[0].world_from_object;
    const float u = t / 2.0f;
    const glm::vec3 at(bezier(0, 1, 3, 0, 2, u), 0.0f, bezier(0, 0, 6, 4, 2, u));
    EXPECT_NEAR(glm::length(glm::vec3(world[3]) - at), 0.0f, 1e-5f) << t;
    EXPECT_NEAR(world[0][0], 2.0f, 1e-6f);  // the child's own scale, under its parent's move
  }
}

TEST(Pose, VerticesWithoutWeightsFollowTheirNode) {
  Model arm = two_bone_arm();
  std::fill(arm.deformations[0].weights.begin(), arm.deformations[0].weights.begin() + 8, 0.0f);  // vertices 0, 1
  const Model posed = pose(arm, 0, 1.0, "arm");
  EXPECT_EQ(posed.meshes[0].positions[0], glm::vec3(5, 0, 0));
  EXPECT_NEAR(posed.meshes[0].positions[1].x, 5.0f, 1e-6f);
}

std::string pose_problem(const Model& model, std::optional<std::size_t> animation = 0) {
  try {
    pose(model, animation, 0.5, "arm.glb");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(Pose, BrokenModelsAreRefusedWithTheirProblem) {
  Model m = two_bone_arm();
  m.nodes[1].parent = 2;  // 1 -> 2 -> 1
  EXPECT_NE(pose_problem(m).find("is its own ancestor"), std::string::npos) << pose_problem(m);
  m = two_bone_arm();
  m.nodes[2].parent = 7;
  EXPECT_NE(pose_problem(m).find("node 2's parent 7 does not exist"), std::string::npos) << pose_problem(m);
  m = two_bone_arm();
  m.skins[0].joints[1] = 9;
  EXPECT_NE(pose_problem(m).find("skin 0's joint 1 is node 9, which does not exist"), std::string::npos);
  m = two_bone_arm();
  m.deformations[0].joints[4 * 9 + 1] = 5;
  EXPECT_NE(pose_problem(m).find("vertex 9 is weighted to joint 5, but skin 0 has 2 joints"), std::string::npos)
      << pose_problem(m);
  m = two_bone_arm();
  m.deformations[0].weights.pop_back();
  EXPECT_NE(pose_problem(m).find("weights for 10 vertices of 4 influences"), std::string::npos) << pose_problem(m);
  m = two_bone_arm();
  m.animations[0].samplers[0].times = {1.0f, 0.0f};
  EXPECT_NE(pose_problem(m).find("animation 'bend', sampler 0: key times do not increase"), std::string::npos);
  m = two_bone_arm();
  m.animations[0].channels[0].node = 3;
  EXPECT_NE(pose_problem(m).find("channel 0 drives node 3, which does not exist"), std::string::npos);
  m = two_bone_arm();
  m.instances[0].skin = 4;
  EXPECT_NE(pose_problem(m, std::nullopt).find("uses skin 4, which does not exist"), std::string::npos);
  EXPECT_THROW(pose(two_bone_arm(), 1, 0.0, "arm.glb"), std::out_of_range);
  EXPECT_THROW(pose(two_bone_arm(), 0, std::nan(""), "arm.glb"), std::invalid_argument);
}

}  // namespace
}  // namespace facet::animation_tests
