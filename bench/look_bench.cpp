// look_bench.cpp - the frame time of each look on one model: the Blinn-Phong headlight look against the physically
// based one lit by the studio, as `facet render` draws them (same framing, samples and threads).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "facet/model_io.hpp"
#include "facet/render_job.hpp"
#include "facet/renderer.hpp"
#include "facet/scene.hpp"
#include "facet/view_spec.hpp"

// The looks: Blinn-Phong's headlight; the physically based look lit by the studio; the same with a key light; with
// the key light's shadows; and with ambient occlusion too.
// Usage: facet_look_bench MODEL WIDTH HEIGHT SAMPLES THREADS ROUNDS FRAMES. Alternates the looks ROUNDS times, each
// round drawing FRAMES frames of each after one warm-up frame, and prints per look the median over rounds of the
// mean milliseconds per frame (clear, draw, finish), and the ratio of each look to the first.
int main(int argc, char** argv) {
  if (argc != 8) {
    std::fprintf(stderr, "usage: %s MODEL WIDTH HEIGHT SAMPLES THREADS ROUNDS FRAMES\n", argv[0]);
    return 2;
  }
  const int width = std::atoi(argv[2]), height = std::atoi(argv[3]), samples = std::atoi(argv[4]);
  const int rounds = std::atoi(argv[6]), frames = std::atoi(argv[7]);
  facet::Renderer renderer(std::atoi(argv[5]));
  facet::Scene scene;
  const auto mesh = std::make_shared<const facet::Mesh>(facet::load_model(argv[1]));
  scene.add({mesh, glm::mat4(1.0f)});
  const facet::View view = facet::make_view(facet::CameraSpec{}, facet::framing_of(*mesh, argv[1]),
                                            static_cast<float>(width) / static_cast<float>(height));
  facet::Framebuffer target(width, height, samples);

  struct Look {
    const char* name;
    facet::SceneOptions options;
  };
  facet::LookSpec phong;
  phong.shading = facet::Shading::blinn_phong;
  const glm::vec3 background = facet::kDefaultBackground;
  // The physically based look with a key light from above front left, then with its shadows.
  facet::LookSpec key;
  key.light_direction = glm::vec3(-0.4f, 1.0f, 0.6f);
  facet::LookSpec shadows = key;
  shadows.shadows = true;
  facet::LookSpec occlusion = shadows;
  occlusion.ambient_occlusion = true;
  const auto options = [&](const facet::LookSpec& look) {
    return facet::scene_options(look, view.view_from_world, facet::Shading::automatic, background);
  };
  const std::vector<Look> looks = {
      {"blinn-phong", options(phong)},
      {"pbr+studio", options(facet::LookSpec{})},
      {"pbr+key", options(key)},
      {"pbr+shadows", options(shadows)},
      {"pbr+shadows+ao", options(occlusion)},
  };
  std::vector<std::vector<double>> times(looks.size());
  for (int round = 0; round < rounds; ++round)
    for (std::size_t l = 0; l < looks.size(); ++l) {
      const auto frame = [&] {
        renderer.clear(target, glm::vec4(background, 1.0f));
        scene.render(renderer, target, view, looks[l].options);
        renderer.finish(target);
      };
      frame();
      const auto start = std::chrono::steady_clock::now();
      for (int i = 0; i < frames; ++i) frame();
      times[l].push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count() /
                         frames);
    }
  std::vector<double> medians;
  for (std::vector<double>& t : times) {
    std::sort(t.begin(), t.end());
    medians.push_back(t[t.size() / 2]);
  }
  for (std::size_t l = 0; l < looks.size(); ++l)
    std::printf("%-15s %8.3f ms  %.2fx\n", looks[l].name, medians[l], medians[l] / medians[0]);
  return 0;
}
