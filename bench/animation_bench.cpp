// animation_bench.cpp - posing a model a frame: 100,000 vertices skinned by 4 joints each, or morphed by 2 targets.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <glm/gtc/matrix_transform.hpp>
#include <optional>

#include "facet/model.hpp"
#include "facet/primitives.hpp"

namespace {

using namespace facet;

constexpr int kBones = 16;

// A torus of 100,000 vertices (normals and uvs as the primitive makes them) in a chain of 16 bones along x, each
// vertex weighted to the 4 bones nearest it; the bones bend about z through a 2 s clip of 9 keys.
Model skinned_torus(bool skinned) {
  Model model;
  Mesh mesh = make_torus(1.0f, 0.35f, 500, 200);
  const float x0 = -1.4f, step = 2.8f / kBones;
  MeshDeformation d;
  if (skinned) {
    d.influences = 4;
    for (const glm::vec3& p : mesh.positions) {
      const float at = (p.x - x0) / step;
      const int nearest = std::clamp(static_cast<int>(at), 0, kBones - 1);
      float total = 0.0f, w[4];
      for (int k = 0; k < 4; ++k) {
        const int bone = std::clamp(nearest - 1 + k, 0, kBones - 1);
        w[k] = 1.0f / (1.0f + std::abs(at - (static_cast<float>(bone) + 0.5f)));
        total += w[k];
        d.joints.push_back(static_cast<std::uint16_t>(bone));
      }
      for (const float v : w) d.weights.push_back(v / total);
    }
  } else {
    d.morph_targets.resize(2);
    for (const glm::vec3& p : mesh.positions) {
      d.morph_targets[0].positions.push_back(glm::vec3(0.0f, 0.2f * p.x * p.x, 0.0f));
      d.morph_targets[1].positions.push_back(glm::vec3(0.1f * p.z, 0.0f, 0.0f));
    }
    d.default_weights = {0.0f, 0.0f};
  }
  model.meshes.push_back(std::move(mesh));
  model.deformations.push_back(std::move(d));
  Skin skin;
  Animation clip{"bend", {}, {}};
  std::vector<float> times;
  for (int k = 0; k <= 8; ++k) times.push_back(0.25f * static_cast<float>(k));
  for (int b = 0; b < kBones; ++b) {
    ModelNode bone;
    bone.parent = b - 1;
    bone.translation = glm::vec3(b == 0 ? x0 : step, 0.0f, 0.0f);
    model.nodes.push_back(bone);
    skin.joints.push_back(static_cast<std::uint32_t>(b));
    skin.inverse_bind_matrices.push_back(
        glm::translate(glm::mat4(1.0f), glm::vec3(-(x0 + step * static_cast<float>(b)), 0.0f, 0.0f)));
    AnimationSampler s{times, {}, 4, Interpolation::linear};
    for (int k = 0; k <= 8; ++k) {
      const float half = 0.05f * std::sin(0.8f * static_cast<float>(k + b));
      s.values.insert(s.values.end(), {0.0f, 0.0f, std::sin(half), std::cos(half)});
    }
    clip.samplers.push_back(s);
    clip.channels.push_back({static_cast<std::uint32_t>(b), static_cast<std::uint32_t>(b), AnimatedProperty::rotation});
  }
  if (!skinned) {
    clip.samplers = {{{0.0f, 2.0f}, {0.0f, 0.0f, 1.0f, 1.0f}, 2, Interpolation::linear}};
    clip.channels = {{0, kBones, AnimatedProperty::weights}};
    model.nodes.push_back(ModelNode{});
  }
  model.skins.push_back(skin);
  model.animations.push_back(clip);
  ModelInstance instance;
  instance.node = skinned ? 0 : kBones;
  instance.skin = skinned ? 0 : -1;
  model.instances.push_back(instance);
  return model;
}

// One frame's pose of the whole model by a Poser, which keeps its memory and threads between frames.
void BM_Skin100kVertices(benchmark::State& state) {
  static const Model model = skinned_torus(true);
  Poser poser(static_cast<int>(state.range(0)));
  double t = 0.0;
  for (auto _ : state) {
    const Model& posed = poser(model, 0, t, "bench");
    benchmark::DoNotOptimize(posed.meshes[0].positions.data());
    t += 1.0 / 30.0;
  }
}
BENCHMARK(BM_Skin100kVertices)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_Morph100kVerticesBy2Targets(benchmark::State& state) {
  static const Model model = skinned_torus(false);
  Poser poser(1);
  double t = 0.1;
  for (auto _ : state) {
    const Model& posed = poser(model, 0, t, "bench");
    benchmark::DoNotOptimize(posed.meshes[0].positions.data());
    t += 1.0 / 30.0;
  }
}
BENCHMARK(BM_Morph100kVerticesBy2Targets)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
